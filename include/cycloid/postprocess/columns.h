#ifndef cycloid_postprocess_columns_h
#define cycloid_postprocess_columns_h

#include <cycloid/results/energy_state.h>
#include <cycloid/results/stage_state.h>

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace cycloid
{
  namespace postprocess
  {
    /**
     * @brief One column of a CSV file: its header name and how a row
     * writes its value (in the file's units, results::units).
     *
     * Why: a file's header and its rows were two lists kept in step by
     * hand (27 and 23 entries for stiffness.csv); as one table a column is
     * added, moved or renamed in one place.
     */
    template <typename Row>
    struct Column
    {
      /** Header name, with the unit as its suffix (`torque_Nm`). */
      const char *name;
      /** Write the value of @p row to @p out (no separator). */
      std::function<void(std::ostream &out, const Row &row)> write;
    };

    /** What a row of `stiffness.csv` is made of. */
    struct StiffnessRow
    {
      const results::StageState &state;   ///< The state.
      bool                       flagged; ///< Report::flag() of the state.
      /** The most loaded pin's Hertz width in node spacings (NaN: none). */
      double max_pin_hertz_nodes;
    };

    /** What a row of `pin_forces.csv` is made of. */
    struct PinRow
    {
      const results::StageState &state; ///< The state.
      const results::PinState   &pin;   ///< One of its pins.
    };

    /** What a row of `bearing_forces.csv` is made of. */
    struct BearingRow
    {
      const results::StageState   &state;   ///< The state.
      const results::BearingState &bearing; ///< One of its bearings.
    };

    /** What a row of `energy.csv` is made of. */
    struct EnergyRow
    {
      const results::EnergyState &energy; ///< The step's energies.
      const results::StageState  &state;  ///< The step's state.
    };

    /** The columns of `stiffness.csv`, in file order. */
    const std::vector<Column<StiffnessRow>> &
    stiffness_columns();

    /** The columns of `pin_forces.csv`, in file order. */
    const std::vector<Column<PinRow>> &
    pin_force_columns();

    /** The columns of `bearing_forces.csv`, in file order. */
    const std::vector<Column<BearingRow>> &
    bearing_columns();

    /** The columns of `compliance_breakdown.csv`, in file order (a row is
     * a state). */
    const std::vector<Column<results::StageState>> &
    breakdown_columns();

    /** The columns of `energy.csv`, in file order. */
    const std::vector<Column<EnergyRow>> &
    energy_columns();

    /** The header line of @p columns (names joined by commas). */
    template <typename Row>
    std::string
    header(const std::vector<Column<Row>> &columns)
    {
      std::string line;
      for (const auto &c : columns)
        line += (line.empty() ? "" : ",") + std::string(c.name);
      return line;
    }

    /** Write @p row as one line of @p columns to @p out. */
    template <typename Row>
    void
    write_row(std::ostream                   &out,
              const std::vector<Column<Row>> &columns,
              const Row                      &row)
    {
      bool first = true;
      for (const auto &c : columns)
        {
          if (!first)
            out << ',';
          first = false;
          c.write(out, row);
        }
      out << '\n';
    }
  } // namespace postprocess
} // namespace cycloid

#endif

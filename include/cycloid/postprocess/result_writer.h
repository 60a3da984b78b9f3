#ifndef cycloid_postprocess_result_writer_h
#define cycloid_postprocess_result_writer_h

#include <deal.II/base/numbers.h>

#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include <mpi.h>

namespace cycloid
{
  namespace postprocess
  {
    /**
     * @brief One row of `stiffness.csv`: a solved load state. Column names
     * are those of the contract (shared/contract.md) plus a few extras.
     */
    struct StiffnessRow
    {
      unsigned int step            = 0;
      double       crank_deg       = 0;
      double       torque_Nm       = 0;
      double       rotation_rad    = 0;
      double       k_secant        = 0; ///< T / beta [N m/rad]
      double       k_tangent       = 0; ///< dT/dbeta [N m/rad]
      unsigned int pins_in_contact = 0;
      unsigned int iterations      = 0; ///< active-set (FE) or
                                        ///< load-balance iterations
      unsigned long dofs               = 0;
      double        wall_s             = 0;
      double        takeup_rad         = 0; ///< rigid lost motion
      double        k_secant_elastic   = 0; ///< T / (beta - takeup)
      double        reaction_torque_Nm = 0; ///< sum F * arm
      double        max_pin_force_N    = 0;
      /** CG iterations of all linear solves of the state. */
      unsigned long linear_iterations = 0;
      /** Peak resident memory of the run so far, summed over the ranks
       * (VmHWM) [MB]. */
      double peak_memory_MB = 0;
    };

    /** Peak resident memory (VmHWM) summed over the ranks of @p comm [MB]. */
    double
    peak_memory_MB(const MPI_Comm comm);

    /**
     * @brief One row of `pin_forces.csv`: one pin against one disc in one
     * state. Fx, Fy: force of the pin on the disc in the housing frame.
     */
    struct PinForceRow
    {
      unsigned int step         = 0;
      double       crank_deg    = 0;
      unsigned int disc         = 0;
      unsigned int pin          = 0;
      double       fx_N         = 0;
      double       fy_N         = 0;
      double       fn_N         = 0;
      double       arm_mm       = 0; ///< signed, positive resists +T
      double       clearance_um = 0; ///< initial normal gap before load
      double       phase_deg    = 0; ///< tooth phase, 0 at the root
      double       approach_um  = 0; ///< beta * arm - clearance, >= 0
      double       pair_stiffness_N_per_mm = 0;
      double       contact_x_mm            = 0;
      double       contact_y_mm            = 0;
      /** Contact half-width of the model [um]: FE, from the extent of the
       * active nodes; analytical, Hertz's. */
      double contact_halfwidth_um = 0;
      /** Hertz half-width a = sqrt(4 F R* / (pi b E*)) for this pin's
       * force and curvatures [um]. */
      double hertz_halfwidth_um = 0;
    };

    /** Radians per arcminute. */
    constexpr double rad_per_arcmin = dealii::numbers::PI / (180. * 60.);

    /**
     * @brief Writes `stiffness.csv` and `pin_forces.csv` (one header line,
     * then rows flushed as each state is solved, so a run that stops early
     * leaves valid files). Only an active writer (MPI rank 0) touches the
     * files.
     */
    /** One stiffness.csv line (columns of ResultWriter::stiffness_header). */
    void
    write_stiffness_row(std::ostream &out, const StiffnessRow &row);

    /** One pin_forces.csv line (columns of ResultWriter::pin_forces_header). */
    void
    write_pin_force_row(std::ostream &out, const PinForceRow &row);

    class ResultWriter
    {
    public:
      /** Create @p directory if needed and write the headers. */
      ResultWriter(const std::string &directory, const bool active);

      /** Append one state. */
      void
      write(const StiffnessRow &state, const std::vector<PinForceRow> &pins);

      /** Header line of stiffness.csv. */
      static std::string
      stiffness_header();

      /** Header line of pin_forces.csv. */
      static std::string
      pin_forces_header();

    private:
      const bool    active;
      std::ofstream stiffness;
      std::ofstream pin_forces;
    };
  } // namespace postprocess
} // namespace cycloid

#endif

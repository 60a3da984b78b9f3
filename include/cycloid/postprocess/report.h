#ifndef cycloid_postprocess_report_h
#define cycloid_postprocess_report_h

#include <cycloid/postprocess/catalogue.h>
#include <cycloid/postprocess/sweep_noise.h>
#include <cycloid/results/energy_state.h>
#include <cycloid/results/stage_state.h>

#include <cstdint>
#include <fstream>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include <mpi.h>

namespace cycloid
{
  namespace postprocess
  {
    /** Mean, minimum, maximum and (max - min) / mean of a series. */
    struct Statistics
    {
      double mean        = 0; ///< Mean.
      double min         = 0; ///< Smallest value.
      double max         = 0; ///< Largest value.
      double fluctuation = 0; ///< (max - min) / mean.

      /** The statistics of @p values (not empty). */
      explicit Statistics(const std::vector<double> &values);
    };

    /**
     * @brief The one place where solved states become files and console
     * lines, for every model and run: `stiffness.csv` and `pin_forces.csv`
     * (one header line, then rows flushed as each state is written, so a
     * run that stops early leaves valid files), `fluctuation.csv` when the
     * states cover several crank angles, `energy.csv` for transient runs,
     * and the one-line console summary of a state. Unit conversions from
     * the state's units to the columns' happen here (results::units).
     *
     * Only rank 0 of the communicator writes or prints. The output
     * directory exists already (the app makes it once).
     */
    class Report
    {
    public:
      /** What the report writes. */
      struct Options
      {
        /** Output directory (must exist). */
        std::string directory = "output";
        /** The states' loads are rotations (fluctuation.csv's first
         * column) rather than torques. */
        bool rotation_control = false;
        /** Write energy.csv (transient runs). */
        bool energy = false;
        /** Write bearing_forces.csv (Crank bearings = needle). */
        bool bearings = false;
        /** Write compliance_breakdown.csv (models that split the
         * rotation: analytic and reduced). */
        bool breakdown = false;
        /** Write fluctuation.csv when the states of a load cover several
         * crank angles (phase sweeps; not for a transient, whose load
         * changes from step to step). */
        bool fluctuation = true;
        /** The states come from a discretised model (FE), whose phases
         * carry mesh-to-mesh noise: fluctuation.csv estimates its floor.
         * False for the analytic model (floor 0). */
        bool discretised = true;
        /** A sweep repeated one contact level finer: K_tangent of
         * each load over the phases in the previous pass, in the order of
         * the loads (empty: none). The noise floor is then the change
         * between the passes (postprocess::sweep_noise). */
        std::vector<std::vector<double>> coarser_k_tangent;
        /** The sweep runs under Mesh/Target accuracy, which decides after
         * the fluctuation is printed whether to repeat the sweep finer: an
         * unresolved fluctuation's warning defers to it. */
        bool sweep_target = false;
        /** The states are a catalogue torque cycle (Loading/Torque cycle):
         * write torsion_curve.csv and rigidity.csv. */
        bool torque_cycle = false;
        /** Rated torque of the cycle [N m]. */
        double rated_torque = 0;
        /** Fraction of the rated torque at which the lost motion is read
         * (catalogues: 3 %). */
        double lost_motion_fraction = 0.03;
        /** Warn about pins whose peak contact pressure exceeds this
         * (Material/Allowable contact pressure; 0: never) [MPa]. */
        double allowable_pressure = 0;
        /** Flag FE states whose largest error estimate exceeds this
         * (Mesh/Warning threshold; 0: never) [-]. */
        double warning_threshold = 0;
        /** What cures a flagged state, named in its warning (e.g. the
         * entries to raise, with their present values). */
        std::string refine_advice;
        /** Continue the files of a run being resumed instead of starting
         * them: truncate each to the size in @p resume_sizes (the sizes at
         * the checkpoint, in the order of files()), then append. */
        bool resume = false;
        std::vector<std::uintmax_t>
          resume_sizes; ///< Sizes of files() at the checkpoint [bytes].
      };

      /** Open (or, resuming, truncate and reopen) the files on rank 0. */
      Report(const Options &options, const MPI_Comm comm);

      /** The CSV files this report writes, in a fixed order. */
      std::vector<std::string>
      files() const;

      /** Their current sizes in bytes (for a checkpoint; rank 0). */
      std::vector<std::uintmax_t>
      file_sizes() const;

      /**
       * Append @p state to stiffness.csv and pin_forces.csv, and keep its
       * stiffness for fluctuation.csv under its load value @p load (torque
       * [N m] or rotation [rad]: the states of one load over the crank
       * angles form one series).
       */
      void
      write(const results::StageState &state, const double load);

      /** Append @p row to energy.csv. */
      void
      write(const results::EnergyState &row, const results::StageState &state);

      /** Print the one-line summary of @p state after @p prefix. */
      void
      print(const results::StageState &state, const std::string &prefix) const;

      /** If the states covered more than one crank angle: write
       * fluctuation.csv and print the stiffness and transmission error over
       * the period per load. For a torque cycle: write torsion_curve.csv and
       * rigidity.csv and print the catalogue figures. Then name the most
       * loaded pin of the run and the files written. */
      void
      finish() const;

      /** A sweep's largest noise floor over its fluctuation, over the
       * loads of more than one crank angle (the fluctuation is resolved
       * where this is below 1/2; NaN if some floor is unknown; 0 without
       * a mesh or on ranks other than 0). */
      double
      noise_ratio() const;

      /** K_tangent over the phases, one series per load in the order
       * first written (rank 0; empty elsewhere). */
      std::vector<std::vector<double>>
      k_tangent_series() const;

      /** Header line of stiffness.csv. */
      static std::string
      stiffness_header();

      /** Header line of pin_forces.csv. */
      static std::string
      pin_forces_header();

      /** Header line of energy.csv. */
      static std::string
      energy_header();
      /** Header line of torsion_curve.csv. */
      static std::string
      torsion_curve_header();
      /** Header line of rigidity.csv. */
      static std::string
      rigidity_header();

    private:
      /** The stiffness and rotation of one load over the crank angles, in
       * order. */
      struct Series
      {
        double              load = 0;
        std::vector<double> crank, k_tangent, k_secant, rotation;
      };
      /** The most loaded pin of the run and the state it was in. */
      struct PeakPin
      {
        unsigned int      step   = 0;
        double            crank  = 0;
        double            torque = 0;
        results::PinState pin;
      };
      /** Whether @p state exceeds the warning threshold: its error
       * estimate, or, for a state without one, its resolution indicator
       * (results::resolution_error()); a failed estimate always. */
      bool
      flag(const results::StageState &state) const;
      /** The hertz_nodes of @p state's most loaded pin (NaN: none). */
      static double
      max_pin_hertz_nodes(const results::StageState &state);
      /** Print @p state's error estimate, and its warning if flagged. */
      void
      print_estimate(const results::StageState &state) const;
      /** For a state without an estimate: print its contact resolution,
       * and its warning if flagged. */
      void
      print_resolution(const results::StageState &state) const;
      /** The noise figures of series @p i (sweeps). */
      SweepNoise
      noise(const unsigned int i) const;
      /** Write fluctuation.csv and print its figures (sweeps). */
      void
      write_fluctuation() const;
      /** Print whether a sweep's fluctuation stands above its noise
       * floor, and what to do when it does not. */
      void
      print_noise(const SweepNoise &noise) const;
      /** Write torsion_curve.csv and rigidity.csv and print the catalogue
       * figures (torque cycles). */
      void
      write_torque_cycle() const;

      /** Print the run's most loaded pin, its pin of highest contact
       * pressure, and the warning if that is above the allowable. */
      void
      print_peaks() const;

      const Options             options;
      const bool                active;
      std::ofstream             stiffness;
      std::ofstream             pin_forces;
      std::ofstream             energy;
      std::ofstream             bearing_forces;
      std::ofstream             breakdown;
      std::vector<Series>       series;
      std::vector<TorsionPoint> cycle;
      PeakPin                   peak;
      /** The pin with the highest contact pressure of the run. */
      PeakPin peak_pressure;
      /** States with a pin above Options::allowable_pressure. */
      unsigned int n_overloaded = 0;
      /** States flagged by the warning threshold, and states written. */
      unsigned int n_flagged = 0, n_written = 0;
    };
  } // namespace postprocess
} // namespace cycloid

#endif

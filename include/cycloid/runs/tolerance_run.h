#ifndef cycloid_runs_tolerance_run_h
#define cycloid_runs_tolerance_run_h

#include <cycloid/parameters/loading.h>
#include <cycloid/reduced/reduced_model.h>
#include <cycloid/results/cost_figures.h>
#include <cycloid/results/stage_state.h>
#include <cycloid/tolerance/sampler.h>
#include <cycloid/tolerance/tolerance_parameters.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <mpi.h>

namespace cycloid
{
  namespace runs
  {
    /**
     * @brief `Run = tolerance`: a Monte-Carlo study of the stage under
     * manufacturing tolerances (doc/tolerance.md).
     *
     * Sample 0 is the stage of the parameter file (its deviation files,
     * if any, are the mean); samples 1 ... n draw random deviations from
     * the bands of `Tolerance study` (tolerance::Sampler). Every sample is
     * solved at every crank angle and torque of `Loading` by the reduced
     * model on the compliance condensed once for sample 0
     * (reduced::ReducedModel's sample constructor), or by the analytical
     * model. Sample s runs on rank s mod (number of ranks), and its draws
     * depend on the seed and s alone, so any number of ranks gives the
     * same samples. Rank 0 gathers them and writes `samples.csv`,
     * `tolerance_summary.csv`, `pin_force_summary.csv`,
     * `tolerance_sensitivity.csv` and `extreme-samples/`.
     */
    template <int dim>
    class ToleranceRun
    {
    public:
      /** What the run reads from the parameter file. */
      struct Settings
      {
        /** The reduced model of the mean stage (its coarse model and scene;
         * the analytical model reads its stage settings). */
        reduced::ReducedSettings       model;
        parameters::LoadingParameters  loading; ///< Torques, crank angles.
        tolerance::ToleranceParameters study; ///< Subsection `Tolerance study`.
      };

      /** Check the scene and the study. */
      ToleranceRun(const Settings &settings, const MPI_Comm comm);

      /** Solve every sample and write the study. */
      void
      run();

    private:
      /** A sample's states (each crank angle, each torque, in order) for
       * the stage with @p deviations; throws if it cannot be solved (a
       * pin overlaps a disc at rest). */
      using SampleSolver = std::function<std::vector<results::StageState>(
        const tolerance::StageDeviations &deviations)>;

      /** What one study (all samples with some bands on) gives rank 0. */
      struct Study
      {
        /** Per sample: per state K_secant, K_tangent, rotation, max pin
         * force, pins in contact, then Fn of every (disc, pin); then the
         * sample's figures over states (cycle_figures()); empty if the
         * sample could not be solved. */
        std::vector<std::vector<double>> figures;
        /** Per sample: its samples.csv rows (empty if not kept). */
        std::vector<std::string> rows;
        /** Per sample: why it could not be solved (empty if it was). */
        std::vector<std::string> failures;
        /** Wall time of the slowest rank [s]. */
        double wall_s = 0;
      };

      /** Figures per state in Study::figures before the pin forces. */
      static constexpr unsigned int n_figures = 5;

      /**
       * The figures of a sample that several of its states make, with
       * the name, crank angle [deg] and torque [N m] of their summary
       * rows: with `Loading/Torque cycle`, per crank angle the catalogue's
       * torsional rigidity, lost motion and backlash
       * (postprocess::catalogue_figures()); over several crank angles,
       * per torque the transmission error's peak-to-peak (the spread of
       * the output rotation over the angles; its crank angle NaN).
       */
      struct OverStates
      {
        std::string name;   ///< Its quantity name in the summary.
        double      crank;  ///< Crank angle [deg] (NaN: over all).
        double      torque; ///< Torque [N m] (the rated one for a cycle).
      };

      /** The figures over states of this study, in Study::figures' order. */
      std::vector<OverStates>
      over_states() const;

      /** The values of over_states() for a sample's @p states. */
      std::vector<double>
      cycle_figures(const std::vector<results::StageState> &states) const;

      /** The side(s) the torques load: +1, -1, or 0 for both. */
      int
      load_sign() const;

      /**
       * Solve every torque of one crank angle in order, each from the
       * rotation of the one before, by @p solve (torque [N m], rotation
       * guess [rad]); a torque cycle's zero torque is the limit of its
       * side, @p limit (+1, -1). Each load becomes a state by @p state_of
       * and is appended to @p states, its wall time counted from @p start
       * (the first: the crank angle's set-up as well).
       */
      void
      add_torques(
        results::Clock::time_point                                start,
        const std::function<analytic::LoadState(double, double)> &solve,
        const std::function<analytic::LoadState(int)>            &limit,
        const std::function<results::StageState(const analytic::LoadState &)>
                                         &state_of,
        std::vector<results::StageState> &states) const;

      /** The solver of the reduced model: condenses the mean stage at every
       * crank angle (collective); a sample then costs its own gaps and a
       * small complementarity solve per torque. */
      SampleSolver
      reduced_solver();

      /** The solver of the analytical model. */
      SampleSolver
      analytic_solver() const;

      /** One state's states of a sample on @p solve as figures (and its
       * samples.csv rows if @p rows). */
      std::vector<double>
      figures_of(const std::vector<results::StageState> &states) const;

      /** Every sample drawn with the bands @p on, solved by @p solve on
       * its rank, gathered on rank 0 (collective); @p label: the
       * console's name of the study, @p keep_rows: format samples.csv. */
      Study
      solve_study(const SampleSolver        &solve,
                  const tolerance::BandMask &on,
                  const std::string         &label,
                  const bool                 keep_rows);

      /** The console's first line: the study, the scene, the bands. */
      void
      announce() const;

      /** The console's account of @p study: its cost, per state the load
       * sharing and the peak pin force, the samples left out. */
      void
      print_outcome(const Study &study) const;

      /** Figure @p i (an index into Study::figures' rows) of every
       * solved sample of @p study but the mean. */
      static std::vector<double>
      drawn(const Study &study, const unsigned int i);

      /** Write samples.csv, the summaries and the extreme samples of
       * @p study (rank 0). */
      void
      write_study(const Study &study) const;

      /** Write tolerance_summary.csv and pin_force_summary.csv. */
      void
      write_summaries(const Study &study) const;

      /** Write extreme-samples/: the samples at the extremes of K_secant
       * and of the peak pin force, as deviation files, and their list. */
      void
      write_extremes(const Study &study) const;

      /** Write tolerance_sensitivity.csv from the full @p study and the
       * studies of one band each, @p alone (band, study) (rank 0). */
      void
      write_sensitivity(
        const Study                                       &study,
        const std::vector<std::pair<unsigned int, Study>> &alone) const;

      const Settings            settings;
      const MPI_Comm            comm;
      const std::vector<double> angles;
      const std::vector<double> torques;
      const unsigned int        n_pins;
      const unsigned int        n_discs;
      const tolerance::Sampler  sampler;
      /** The reduced model of the mean stage at each crank angle. */
      std::vector<std::unique_ptr<reduced::ReducedModel<dim>>> nominal;
    };
  } // namespace runs
} // namespace cycloid

#endif

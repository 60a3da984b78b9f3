#ifndef cycloid_runs_reduced_run_h
#define cycloid_runs_reduced_run_h

#include <cycloid/parameters/loading.h>
#include <cycloid/postprocess/report.h>
#include <cycloid/reduced/reduced_model.h>

#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <mpi.h>

namespace cycloid
{
  namespace runs
  {
    /**
     * @brief `Run = reduced`: the reduced model (reduced::ReducedModel)
     * over every crank angle of `Loading` and every torque, like
     * `analytic`: one condensation of the coarse FE model per crank angle
     * (collective on every rank), then every torque as a small
     * complementarity solve warm-started from the previous one.
     */
    template <int dim>
    class ReducedRun
    {
    public:
      /** What the run reads from the parameter file. */
      struct Settings
      {
        reduced::ReducedSettings      model;   ///< The reduced model.
        parameters::LoadingParameters loading; ///< Torques and crank angles.
      };

      /** Check the scene (the geometry and the analytical model). */
      ReducedRun(const Settings &settings, const MPI_Comm comm);

      /** Solve and write every state. */
      void
      run();

    private:
      /** The side(s) the torques load: +1, -1, or 0 for both. */
      int
      load_sign() const;

      /**
       * Before the first condensation: print the contacts it will condense
       * (and why both flanks, for torques of both signs) with the cost
       * model's memory and time, and stop if the memory does not fit
       * (stage::estimate_reduced_cost(), stage::check_reduced_memory()).
       * Collective.
       */
      void
      announce_cost(const reduced::CoarseModel<dim> &coarse,
                    const std::vector<double>       &angles) const;

      /** The report's options: a reduced run's states are not
       * discretised (no contact mesh), and the torque cycle's. */
      postprocess::Report::Options
      report_options() const;

      /** The interpolated compliance over @p angles if the sweep has more
       * crank angles than `Reduced/Anchor angles` (condensed at the
       * anchors, with @p progress; @p verbose: say so), else null. */
      std::unique_ptr<reduced::CompliancePath<dim>>
      compliance_path(const reduced::ReducedSettings &s,
                      reduced::CoarseModel<dim>      &coarse,
                      const std::vector<double>      &angles,
                      std::ostream                   *progress,
                      const bool                      verbose) const;

      /**
       * Every state of the run (each crank angle of @p angles [rad] and
       * each torque) on @p coarse, a coarse model of @p s, handed to
       * @p visit with its torque's index, in order. A state's wall_s is its
       * own work once the mesh exists: its solve, and for the first torque
       * at a crank angle that angle's condensation (an anchored sweep's
       * condensation goes to the first state). @p verbose: the crank
       * angles' console lines.
       */
      void
      solve_states(const reduced::ReducedSettings          &s,
                   reduced::CoarseModel<dim>               &coarse,
                   const std::vector<double>               &angles,
                   const bool                               verbose,
                   const std::function<void(results::StageState &,
                                            unsigned int)> &visit) const;

      /**
       * The error estimate's companion: every state of the run solved on
       * a coarse model one level coarser than @p fine
       * (reduced::ReducedSettings::coarser()), built, solved and freed
       * here. If it fails, the states it reached, and the reason in
       * @p failure.
       */
      std::vector<results::StageState>
      companion_states(const reduced::CoarseModel<dim> &fine,
                       const std::vector<double>       &angles,
                       std::string                     &failure) const;

      /** Torque @p t of @p torques at @p crank_angle [rad] on @p phase,
       * from the rotation @p beta of the state before [rad] (a torque
       * cycle's zero: the limit from its side); an error names state
       * @p step, the crank angle and the torque. */
      analytic::LoadState
      solve_state(reduced::ReducedModel<dim> &phase,
                  const std::vector<double>  &torques,
                  const unsigned int          t,
                  const double                crank_angle,
                  const unsigned int          step,
                  const double                beta) const;

      const Settings             settings;
      const MPI_Comm             comm;
      const analytic::StageModel model;
    };
  } // namespace runs
} // namespace cycloid

#endif

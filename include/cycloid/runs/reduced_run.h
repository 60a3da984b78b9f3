#ifndef cycloid_runs_reduced_run_h
#define cycloid_runs_reduced_run_h

#include <cycloid/parameters/loading.h>
#include <cycloid/postprocess/report.h>
#include <cycloid/reduced/reduced_model.h>

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
       * anchors, with @p progress), else null. */
      std::unique_ptr<reduced::CompliancePath<dim>>
      compliance_path(reduced::CoarseModel<dim> &coarse,
                      const std::vector<double> &angles,
                      std::ostream              *progress) const;

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

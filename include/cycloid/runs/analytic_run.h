#ifndef cycloid_runs_analytic_run_h
#define cycloid_runs_analytic_run_h

#include <cycloid/analytic/stage_model.h>
#include <cycloid/parameters/loading.h>
#include <cycloid/postprocess/report.h>
#include <cycloid/results/stage_state.h>

#include <mpi.h>

namespace cycloid
{
  /**
   * The run modes: each composes a model (analytic::StageModel or
   * stage::StageScene) with the load states of the prm and hands every
   * solved state to postprocess::Report. A run is built first (which
   * checks the scene and throws for one that cannot be solved), then the
   * app makes the output directory, then run() solves and writes.
   */
  namespace runs
  {
    /**
     * Whether the console shows the state of crank angle @p k of @p n_k
     * and torque @p t of @p n_t (runs of many cheap states): all of a short
     * run; of a long one, every torque at about ten crank angles including
     * the first and last; a torque cycle of more than 20 states: about
     * twenty of them, at the first and the last crank angle; and any state
     * with @p always (the rated-torque states of a cycle).
     */
    bool
    show_state(const unsigned int k,
               const unsigned int n_k,
               const unsigned int t,
               const unsigned int n_t,
               const bool         always = false);

    /** Print @p state (its `step` counts crank angle by crank angle, @p n_t
     * torques each, over @p n_k crank angles; @p t its torque) through
     * @p report as "  state i/n: ..." if show_state() says so (@p always:
     * a rated-torque state). */
    void
    print_if_shown(const postprocess::Report &report,
                   const results::StageState &state,
                   const unsigned int         n_k,
                   const unsigned int         t,
                   const unsigned int         n_t,
                   const bool                 always);

    /**
     * @brief `Run = analytic`: the analytical model over every crank angle
     * of `Loading` and every torque (torques warm-started from the
     * previous state), on rank 0 only (other ranks check the geometry
     * alike, then wait).
     */
    class AnalyticRun
    {
    public:
      /** What the run reads from the parameter file. */
      struct Settings
      {
        analytic::ModelSettings       model;     ///< The analytical model.
        parameters::LoadingParameters loading;   ///< Torques and crank angles.
        std::string output_directory = "output"; ///< Where the results go.
      };

      /** Build the model (checking the geometry). */
      AnalyticRun(const Settings &settings, const MPI_Comm comm);

      /** Solve and write every state. */
      void
      run();

    private:
      const Settings             settings;
      const MPI_Comm             comm;
      const analytic::StageModel model;
    };
  } // namespace runs
} // namespace cycloid

#endif

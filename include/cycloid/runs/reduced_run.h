#ifndef cycloid_runs_reduced_run_h
#define cycloid_runs_reduced_run_h

#include <cycloid/parameters/loading.h>
#include <cycloid/reduced/reduced_model.h>

#include <string>

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

      const Settings             settings;
      const MPI_Comm             comm;
      const analytic::StageModel model;
    };
  } // namespace runs
} // namespace cycloid

#endif

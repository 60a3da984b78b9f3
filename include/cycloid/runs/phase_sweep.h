#ifndef cycloid_runs_phase_sweep_h
#define cycloid_runs_phase_sweep_h

#include <cycloid/runs/quasi_static.h>

#include <memory>
#include <vector>

#include <mpi.h>

namespace cycloid
{
  namespace runs
  {
    /**
     * @brief `Run = phase-sweep`: the quasi-static FE contact at `Number of
     * phases` crank angles over one mesh period 360/zp degrees (both ends
     * included), each load warm-started from the previous phase's active
     * set at that load. Each phase has its own mesh (the periodic meshes of
     * `Mesh/Periodic` make phases one period apart identical). Rows are
     * flushed per state, progress and the remaining time are printed, and
     * fluctuation.csv gets the stiffness over the period per load.
     */
    template <int dim>
    class PhaseSweepRun
    {
    public:
      /** Build the first phase's scene (checking it). */
      PhaseSweepRun(const FeRunSettings &settings, const MPI_Comm comm);

      /** Solve and write every phase and load. */
      void
      run();

    private:
      const FeRunSettings                     settings;
      const MPI_Comm                          comm;
      const std::vector<double>               angles;
      std::unique_ptr<stage::StageScene<dim>> first;
    };
  } // namespace runs
} // namespace cycloid

#endif

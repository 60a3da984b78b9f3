#ifndef cycloid_runs_phase_sweep_h
#define cycloid_runs_phase_sweep_h

#include <cycloid/runs/phase_groups.h>
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
     *
     * With `Loading/Ranks per phase group` the ranks split into groups
     * (PhaseGroups), each solving a contiguous block of phases on its own
     * communicator; the states travel to world rank 0 (StateCollector),
     * which prints each as it arrives and writes every file through one
     * postprocess::Report in phase order, so the files have the layout of
     * a one-group sweep. Each group writes the solution files of its
     * states under their global step numbers; world rank 0's
     * solution.pvd lists them all in order.
     */
    template <int dim>
    class PhaseSweepRun
    {
    public:
      /** Split the ranks into groups and build each group's first
       * phase's scene (checking it). */
      PhaseSweepRun(const FeRunSettings &settings, const MPI_Comm comm);

      /** Solve this group's phases; world rank 0 writes every phase and
       * load. */
      void
      run();

    private:
      /** The scene of phase @p k on this rank's group. */
      std::unique_ptr<stage::StageScene<dim>>
      make_scene(const unsigned int k) const;

      const MPI_Comm            comm;
      const std::vector<double> angles;
      const PhaseGroups         groups;
      /** The run's settings; quiet scenes outside world rank 0's group. */
      const FeRunSettings                     settings;
      std::unique_ptr<stage::StageScene<dim>> first;
    };
  } // namespace runs
} // namespace cycloid

#endif

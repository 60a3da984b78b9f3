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
     *
     * With `Mesh/Target accuracy` the sweep also answers for its
     * fluctuation: while the K_tangent fluctuation of some load is not
     * resolved (below twice its noise floor, postprocess::sweep_noise),
     * the whole sweep is repeated with every phase refined one contact
     * level beyond the finest phase of the pass before, at most
     * `Mesh/Maximum sweep refinements` times. From the second pass
     * the floor is the change of the K_tangent curve since the pass
     * before, which measures the mesh's part directly; the repeats stop
     * early when the rate at which it fell says the remaining passes
     * cannot bring it low enough. Each pass rewrites the files; the console
     * says what was done, what it cost and whether the fluctuation is resolved.
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
      /** The scene of phase @p k on this rank's group, meshed with
       * @p s. */
      std::unique_ptr<stage::StageScene<dim>>
      make_scene(const unsigned int k, const FeRunSettings &s) const;

      /** One pass over the phases with @p s, starting with this group's
       * first scene @p first_scene: solve, write every file (world rank 0).
       * @p k_tangent holds the previous pass's K_tangent per load (empty
       * on the first pass; the noise floor is then the change from it)
       * and returns this pass's (world rank 0). Returns, on every rank,
       * the largest ratio floor / fluctuation over the loads (resolved:
       * below 1/2; NaN: a floor unknown). @p finest returns the finest
       * contact level of any phase (every rank). */
      double
      sweep(const FeRunSettings                    &s,
            std::unique_ptr<stage::StageScene<dim>> first_scene,
            std::vector<std::vector<double>>       &k_tangent,
            unsigned int                           &finest) const;

      /** Whether another pass is worth its cost after pass @p pass (at
       * Contact refinements @p level; the next would be at @p next), whose
       * noise ratio was @p ratio and the one before @p previous (NaN when
       * the two do not compare: the first pass's floor is the roughness,
       * the later ones' the change between passes); prints the
       * decision. */
      bool
      sweep_again(const unsigned int pass,
                  const unsigned int level,
                  const unsigned int next,
                  const double       ratio,
                  const double       previous) const;

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

#ifndef cycloid_stage_cost_estimate_h
#define cycloid_stage_cost_estimate_h

#include <deal.II/base/types.h>

#include <cycloid/mesh/mesh_parameters.h>

#include <string>

#include <mpi.h>

namespace cycloid
{
  namespace stage
  {
    /** What the cost of an FE scene depends on. */
    struct CostInputs
    {
      unsigned int                    dimension = 2; ///< Scene/Dimension.
      unsigned int                    n_discs   = 1; ///< Discs in the scene.
      dealii::types::global_dof_index n_dofs = 0; ///< DoFs of the first mesh.
      unsigned int                    degree = 1; ///< Mesh/Polynomial degree.
      unsigned int adaptive_cycles = 0; ///< Mesh/Adaptive refinement cycles.
      unsigned int n_ranks         = 1; ///< MPI ranks.
      /** Mesh/Error estimate: a coarser level is solved too. */
      bool error_estimate = false;
      /** Mesh/Bulk error estimate: the state is solved once more with
       * its bulk cells refined (more DoFs than the state's mesh). */
      bool bulk_estimate = false;
      /** CG with the plain-aggregation W-cycle (Solver/AMG hierarchy,
       * the 3D default): the fits' smoothed hierarchy's memory per DoF
       * times plain_amg_memory. */
      bool plain_amg = false;
      /** The heap gives freed blocks back (elasticity/heap.h; false with
       * CYCLOID_MMAP_THRESHOLD=0, and for the fits' runs): in 3D the
       * memory per DoF times heap_memory. */
      bool heap_released = false;
    };

    /** Memory per DoF (above the ranks' 150 MB) with the plain-aggregation
     * hierarchy relative to the smoothed one the fits were made with:
     * 0.68 on the 3D seed case (1.50 M DoFs) and 0.73 on a 3D two-disc
     * scene of 290 k DoFs, side by side (doc/solver-reuse.md). */
    constexpr double plain_amg_memory = 0.70;

    /** Memory per DoF (above the ranks' 150 MB) in 3D when the heap gives
     * freed matrix-sized blocks and the freed small blocks' pages back,
     * relative to the fits' runs, whose heap kept them: 0.80 on the 3D
     * seed case (1.50 M DoFs, plain-aggregation hierarchy, shared mesh, 2
     * ranks; doc/solver-reuse.md, "The holes of small blocks"). On the
     * distributed mesh the estimate errs high (by 13 % there). Not
     * measured in 2D, where the fit stays, on the safe side. */
    constexpr double heap_memory = 0.82;

    /** DoFs per rank from which heap_memory applies: the DoF count at which
     * a rank frees at least process::give_back_threshold (192 MB) of its
     * heap, where the trim acts. The estimate comes before the heap exists,
     * so it cannot read the free heap itself. Measured: 235-426 MB free at
     * 750 k DoFs a rank (the seed case), 50-130 MB at 145-290 k, where a
     * 3D scene of 290 k DoFs peaked at 1104 MB against 1112 MB with the
     * heap as the libraries left it. */
    constexpr double heap_memory_dofs_per_rank = 500e3;

    /**
     * @brief Estimated peak memory and time of one state of an FE scene,
     * from a cost model fitted to the measured runs of doc/ladder/ladder.csv
     * and, for the 3D times, doc/ladder/retimed-2026-12-06.csv (one state,
     * seed case, this machine; doc/scene-guide.md "Cost model"): per
     * family (2D; 3D one disc; 3D two discs) peak memory = 150 MB per
     * rank + a DoFs (a at 2 ranks 2.68, 3.59, 4.38 kB per DoF, 0.74 of
     * that on 1 rank) and time of a state = c DoFs^p at 2 ranks (p =
     * 2.06, 1.26, 1.16), (2 / ranks)^0.83 on other rank counts.
     * Adaptive cycles add states on meshes 1.15 (2D), 1.28 (3D one disc)
     * or 1.36 (3D two discs) times larger each; degree 2 doubles the
     * memory per DoF and multiplies the time by 1.5 (not fitted: no
     * measured memory for Q2). The error
     * estimate's coarser levels add half a state (measured in 2D: 8 to
     * 46 %, the finest solve starting from the coarser active set).
     * The bulk level of the estimate has 3.7 times the DoFs (the peak
     * memory then is its) and multiplies a 2D state's time by 1.5; in 3D it is
     * costed as one more state on its DoFs.
     */
    struct CostEstimate
    {
      /** Scene family of the fit ("2D", "3D one disc", "3D two discs"). */
      std::string family;
      /** DoFs of the first mesh. */
      dealii::types::global_dof_index n_dofs = 0;
      /** Peak resident memory summed over the ranks [bytes]. */
      double memory_bytes = 0;
      /** Wall time of one solved state (with its adaptive cycles) [s]. */
      double seconds_per_state = 0;

      /** "DoFs N; estimated peak memory M GB (summed over ranks),
       * estimated time T s per state". */
      std::string
      line() const;
    };

    /** The cost model's estimate for @p inputs. */
    CostEstimate
    estimate_cost(const CostInputs &inputs);

    /** What the reduced model's condensation (`Run = reduced`) is costed
     * from, once its coarse model is built. */
    struct ReducedCostInputs
    {
      unsigned int                    dimension = 2; ///< Scene/Dimension.
      dealii::types::global_dof_index n_dofs    = 0; ///< Coarse model DoFs.
      /** Contacts condensed (load cases of one condensation). */
      unsigned int n_contacts = 0;
      /** Crank angles condensed (the anchors of a sweep, or each angle). */
      unsigned int n_condensations = 1;
      /** MPI ranks. */
      unsigned int n_ranks = 2;
    };

    /**
     * @brief The reduced model's cost before it condenses: peak memory and
     * the time of each condensation (factorisation and every load case),
     * fitted to measured 2-rank runs (source/stage/cost_estimate.cc gives
     * the runs and the fit's error; doc/reduced-model.md §4).
     */
    struct ReducedCostEstimate
    {
      ReducedCostInputs inputs; ///< What it was costed from.
      /** Peak resident memory summed over the ranks [bytes]. */
      double memory_bytes = 0;
      /** Wall time of one condensation [s]. */
      double seconds_per_condensation = 0;

      /** "84 contacts on 314028 DoFs: estimated peak memory 1.9 GB (summed
       * over ranks), condensation about 5.4 s (1 crank angle), then about
       * 2 ms per state". */
      std::string
      line() const;
    };

    /** The reduced cost model's estimate for @p inputs. */
    ReducedCostEstimate
    estimate_reduced_cost(const ReducedCostInputs &inputs);

    /**
     * Stop before the condensation if @p estimate needs more than
     * @p available bytes: throws dealii::ExcMessage with the estimate and
     * the entries that reduce it (their present values: the coarse
     * model's element sizes from @p mesh, the axial slices @p slices in
     * 3D). Call with the same arguments on every rank.
     */
    void
    check_reduced_memory(const ReducedCostEstimate  &estimate,
                         const double                available,
                         const mesh::MeshParameters &mesh,
                         const unsigned int          slices);

    /**
     * Memory available to the run [bytes]: /proc/meminfo MemAvailable of
     * each node the ranks of @p comm run on, summed over the nodes, plus
     * what the ranks already hold (VmRSS, part of the estimate). The
     * environment variable CYCLOID_AVAILABLE_MEMORY_MB replaces the whole
     * figure (tests). Collective; infinite if nothing is known.
     */
    double
    available_memory_bytes(const MPI_Comm comm);

    /**
     * Stop before the big matrices are allocated if @p estimate needs more
     * than @p available bytes: throws dealii::ExcMessage with the estimate
     * and the entries of @p mesh that reduce it (their present values).
     * Call with the same arguments on every rank.
     */
    void
    check_memory(const CostEstimate         &estimate,
                 const double                available,
                 const mesh::MeshParameters &mesh);
  } // namespace stage
} // namespace cycloid

#endif

#ifndef cycloid_stage_error_control_loop_h
#define cycloid_stage_error_control_loop_h

#include <deal.II/base/conditional_ostream.h>

#include <deal.II/grid/cell_id.h>

#include <cycloid/mesh/mesh_parameters.h>
#include <cycloid/results/error_estimate.h>
#include <cycloid/results/stage_state.h>
#include <cycloid/stage/stage_scene.h>

#include <optional>
#include <set>
#include <string>
#include <vector>

namespace cycloid
{
  namespace stage
  {
    /**
     * @brief What the solves of one state cost, summed over the mesh
     * levels the error control solved it on.
     */
    struct SolveCost
    {
      unsigned int  iterations = 0; ///< Active-set iterations.
      unsigned long linear     = 0; ///< Linear-solver iterations.
      unsigned int  setups     = 0; ///< Preconditioner set-ups.
      /** Add the cost of the level state @p level. */
      void
      add(const results::StageState &level);
    };

    /**
     * @brief The result of the error control of one state: the state on
     * the mesh asked for (or on the last mesh the target's cycles made),
     * with its error estimate, what its levels cost, and why the control
     * stopped short, if it did.
     */
    struct ControlledState
    {
      /** The state, with StageState::error filled where it was
       * estimated; cost figures are the caller's to copy from #cost. */
      results::StageState state;
      /** The solves of every level. */
      SolveCost cost;
      /** Why a coarser or the bulk level failed (empty: none did). */
      std::string level_failure;
      /** Why a refinement was not made for memory (empty: none). */
      std::string memory_stop;
    };

    /**
     * @brief The error control of one FE state, separate from the scene
     * it works on: the nested contact levels of `Mesh/Error estimate`, the
     * bulk level of `Mesh/Bulk error estimate`, the adaptive cycles and
     * the cycles of `Mesh/Target accuracy` (doc/error-estimate.md).
     *
     * A StageScene knows how to solve a state on its current mesh
     * (StageScene::solve_level()) and how to rebuild its system after the
     * mesh changed; this class decides which meshes to solve on. It
     * coarsens the finest contact level mesh::ErrorControl::coarser_levels
     * times, solves from the coarsest up, refines back, solves the mesh
     * asked for, then (2D by default) refines every cell the contact
     * levels leave alone once, solves and coarsens back, and repeats
     * refine-at-contacts-and-solve while the adaptive cycles or the target
     * ask for it. The mesh is the one asked for (or the last cycle's) when
     * solve() returns, also after a level failed.
     *
     * One object per state: it keeps why the control stopped short and
     * returns it in ControlledState, not in the scene.
     */
    template <int dim>
    class ErrorControlLoop
    {
    public:
      /** The control of @p scene's next state, under the mesh entries
       * @p mesh, printing to @p pcout. */
      ErrorControlLoop(StageScene<dim>                  &scene,
                       const mesh::MeshParameters       &mesh,
                       const dealii::ConditionalOStream &pcout);

      /** Solve the load @p load (as StageScene::solve_level() takes it)
       * on the meshes the error control asks for; see the class
       * description. */
      ControlledState
      solve(const double load);

    private:
      /** The coarser levels of the estimate: coarsen, solve each from the
       * coarsest up (into @p coarser, coarsest first), each warm-started
       * from the one below, and refine back. False if the mesh has too
       * few contact levels (nothing done) or a level failed
       * (level_failure says why; mesh and warm start are restored). */
      bool
      solve_coarser_levels(const double                      load,
                           std::vector<results::StageState> &coarser);
      /** The bulk level: refine once every cell below the two finest
       * levels, solve @p load warm-started from the mesh's active set,
       * coarsen back. False (nothing changed) if it would not fit into
       * the memory available or the solve failed. */
      bool
      solve_bulk_level(const double load, results::StageState &bulk);
      /** The bulk mesh's error of @p fine: from solve_bulk_level(), or
       * none (the console says why). */
      std::optional<results::BulkError>
      measure_bulk_error(const double load, const results::StageState &fine);
      /** After the target's cycles: measure the bulk part again on the
       * mesh @p fine was solved on, and give @p fine its contact levels'
       * estimate (from the two coarser @p levels) plus that part. */
      void
      remeasure_bulk_error(const double                            load,
                           const std::vector<results::StageState> &levels,
                           results::StageState                    &fine);
      /** Solve @p load on the current mesh and add its cost. */
      results::StageState
      solve_level(const double load);
      /** Whether to refine and solve again after cycle @p cycle: the
       * adaptive cycles, or the target not met by @p fine (which has an
       * estimate if @p have_coarse). */
      bool
      refine_again(const unsigned int         cycle,
                   const bool                 have_coarse,
                   const results::StageState &fine) const;
      /** Refine next to the active nodes (up to level_cap()); false if no
       * cell was refined, or if the refined mesh would not fit into the
       * memory available (refinement_fits()). */
      bool
      refine_at_contacts();
      /** Whether the mesh with the refine flags now set fits into the
       * memory available, by the cost model, its DoFs taken in proportion
       * to the active cells; if not, says so and records it in
       * memory_stop, naming the refinement as @p what. The flags must be
       * prepared. Why: in 3D one refinement at every active node
       * multiplied the seed case's DoFs by five (1.5 M to 7.5 M), and the
       * run was killed for memory with its state lost. */
      bool
      refinement_fits(
        const std::string &what = "the next refinement at the contacts");
      /** Coarsen every cell of the finest level; the parents (now active)
       * of the cells coarsened. */
      std::set<dealii::CellId>
      coarsen_finest_level();
      /** Refine the active cells @p cells once. */
      void
      refine_cells(const std::set<dealii::CellId> &cells);
      /** The finest level refine_at_contacts() may reach. */
      unsigned int
      level_cap() const;
      /** Print whether @p s met `Mesh/Target accuracy` (if set). */
      void
      report_accuracy(const results::StageState &s) const;

      StageScene<dim>                          &scene;
      const mesh::MeshParameters               &mesh;
      const dealii::ConditionalOStream         &pcout;
      dealii::parallel::TriangulationBase<dim> &tria;
      const MPI_Comm                            comm;
      /** What the state returns, filled as the control goes. */
      ControlledState out;
    };
  } // namespace stage
} // namespace cycloid

#endif

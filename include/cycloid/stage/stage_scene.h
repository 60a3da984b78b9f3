#ifndef cycloid_stage_stage_scene_h
#define cycloid_stage_stage_scene_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria_base.h>
#include <deal.II/grid/cell_id.h>
#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/analytic/stage_model.h>
#include <cycloid/contact/contact_parameters.h>
#include <cycloid/contact/contact_problem.h>
#include <cycloid/contact/pin_model.h>
#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/mesh/mesh_parameters.h>
#include <cycloid/mesh/stage_mesh.h>
#include <cycloid/parameters/material.h>
#include <cycloid/parameters/scene.h>
#include <cycloid/postprocess/solution_record.h>
#include <cycloid/results/error_estimate.h>
#include <cycloid/results/stage_state.h>
#include <cycloid/stage/cost_estimate.h>

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace cycloid
{
  /**
   * The FE model of the stage, as one object that every FE run composes.
   */
  namespace stage
  {
    /**
     * @brief What a StageScene reads from the parameter file: the stage,
     * its materials, the scene, the mesh, the contact solver, and the
     * analytical model (the warm start of a first state).
     */
    struct StageSettings
    {
      geometry::GeometryParameters   geometry; ///< Subsection `Geometry`.
      parameters::MaterialParameters material; ///< Subsection `Material`.
      parameters::SceneParameters    scene;    ///< Subsection `Scene`.
      mesh::MeshParameters           mesh;     ///< Subsection `Mesh`.
      contact::ContactParameters
        contact; ///< Subsections `Contact` and `Solver`.
      analytic::AnalyticParameters
        analytic; ///< Subsection `Analytic` (warm start).
      /** The loads of solve() are rotations [rad], not torques [N m]. */
      bool rotation_control = false;
      /** The run solves all its states on one operator (a transient run
       * with a fixed step and one scheme matrix): auto's choice of the
       * contact Schur complement (ContactParameters). */
      bool one_operator = false;
      /** Where the solution fields go. */
      std::string output_directory = "output";
      /** Print nothing (the scenes of a phase group other than world rank
       * 0's: the console has one voice). */
      bool quiet = false;

      /** The settings of the analytical model of the same stage. */
      analytic::ModelSettings
      model_settings() const;

      /** The settings of the mesh of the same stage. */
      mesh::MeshSettings
      mesh_settings() const;
    };

    /** One line describing the scene, e.g. "2D, 1 disc(s), elastic
     * pins". */
    std::string
    description(const StageSettings &settings);

    /** Active-set flags with node positions, to warm-start another
     * StageScene (another crank angle) at the same load. */
    template <int dim>
    using ActiveSetSnapshot =
      std::vector<std::pair<contact::SlaveNode<dim>, bool>>;

    /**
     * @brief The FE model of the cycloid stage: the scene's discs (1 or 2;
     * 2D plane strain or 3D) against its pins (rigid, or elastic and held at
     * their cores or in a meshed housing), loaded by a rigid rotation beta
     * of each disc's crank holes (or bore) about the disc's centre, one beta
     * for both discs.
     *
     * It owns the mesh at one placement of the discs, the FE system and
     * contact problem on it, the pin model and the load field, and offers
     * what every run needs: place the discs (place_discs()), solve a load
     * state (solve()) and turn a contact result into the stage's state
     * (state()). Runs (quasi-static, phase sweep, transient) use it; none
     * derives from it.
     *
     * Stages, each timed (step-42's layout): make grid, setup system (DoFs,
     * contact nodes, supports, load), solve (active set), refine at
     * contacts (adaptive cycles), pin forces and output results.
     *
     * Pin supports (contact::PinModel):
     * - `axis`: every DoF within `Pin core radius` of a pin's axis is held
     *   (a rigid core; a line or point constraint would make the pin's
     *   compliance mesh dependent);
     * - `housing`: the housing ring is meshed, its outer surface is held and
     *   each groove (seat) node is glued to its pin's surface in every
     *   component (no slip in the seat; a frictionless seat would leave
     *   each pin free to spin about its axis).
     * Rigid pins hold every pin DoF. The contact problem works per unit
     * thickness in 2D; states are for the whole tooth width.
     */
    template <int dim>
    class StageScene
    {
    public:
      /** Mesh the scene as @p request asks (placement, crank sweep, loaded
       * side), and set up the contact problem on it. Throws, naming the
       * entry, for a scene that cannot be solved. */
      StageScene(const StageSettings     &settings,
                 const mesh::MeshRequest &request,
                 const MPI_Comm           comm);

      /**
       * Place the discs rigidly at crank angle @p psi [rad] while the mesh
       * stays at the request's crank angle (transient runs: the discs follow
       * the crank). Gaps, normals and master points are recomputed;
       * displacements stay in the mesh axes.
       */
      void
      place_discs(const double psi);

      /**
       * Before the first solve, for states that will carry no estimate
       * from nested levels (3D by default, `Error estimate = false`):
       * print the contact resolution they are expected to have at torque
       * @p torque [N m], from the analytical model's most loaded pin (its
       * Hertz width) and this mesh's node spacing at its contact point,
       * and whether Mesh/Warning threshold will flag them
       * (results::resolution_error(); doc/error-estimate.md §6). Nothing
       * under rotation control or at zero torque.
       */
      void
      announce_resolution(const double torque) const;

      /**
       * Solve for output torque @p load [N m] (or, with rotation control,
       * for the rotation @p load [rad]), warm-started from the previous
       * state (or for the first from the analytical model's rotation), with
       * `Mesh/Adaptive refinement cycles` refinements at the active contact.
       * With `Mesh/Error estimate` the state carries its error estimate
       * (the same state on the next coarser contact level, see
       * stage/error_estimate.h), and `Mesh/Target accuracy` refines at the
       * contacts until the estimate is below it.
       */
      results::StageState
      solve(const double load);

      /**
       * The stage's state for a contact result @p result of the current
       * contact problem solved for @p load (as in solve()): pin forces in
       * the housing frame, arms, clearances, contact widths, torque, beta
       * and tangent for the whole tooth width. The cost figures other than
       * iterations and DoFs are the caller's to fill (solve() does).
       */
      results::StageState
      state(const contact::ContactState &result, const double load) const;

      /**
       * The limit of the state as the torque goes to zero from side @p side
       * (+1 or -1) at the current crank angle: the discs turned by the
       * rigid take-up towards that side, no pin force. A frictionless stage
       * at zero torque may rest anywhere between the two limits (its
       * clearance), so a torque cycle reports each zero as its branch's
       * limit; nothing is solved (collective only through the memory
       * figure).
       */
      results::StageState
      zero_torque_limit(const int side) const;

      /** Crank angle of the discs' current placement [rad]. */
      double
      crank_angle() const
      {
        return psi;
      }

      /** The active set with node positions (see warm_start()). */
      ActiveSetSnapshot<dim>
      active_set_snapshot() const;

      /** Warm-start the next solve from another state's active set: each
       * node takes the flag of the nearest node of that state on the same
       * disc and pin (empty: no effect). */
      void
      warm_start(const ActiveSetSnapshot<dim> &snapshot);

      /** Write the last state as solution-NNNN.pvtu for state @p step and
       * add it to @p record, which is rewritten as solution.pvd. */
      void
      output_results(const unsigned int           step,
                     postprocess::SolutionRecord &record);

      /** The contact problem, for a time scheme that steps it. */
      contact::ContactProblem<dim> &
      contact_problem()
      {
        return *contact;
      }

      /** The contact problem (energies, mass products). */
      const contact::ContactProblem<dim> &
      contact_problem() const
      {
        return *contact;
      }

      /** Factor from the contact problem's forces (per unit thickness in
       * 2D) to the whole stage: the tooth width in 2D, 1 in 3D. */
      double
      width_scale() const;

      /** Torque @p torque [N m] of the stage as the contact problem's load
       * (N mm, per unit thickness in 2D). */
      double
      model_torque(const double torque) const;

      /** The contact problem's generalised reaction @p reaction as the
       * stage's torque [N m]. */
      double
      stage_torque(const double reaction) const;

      /** The discs' unit rigid rotation about their centres at the mesh
       * placement (owned entries; zero on other bodies). */
      const dealii::TrilinosWrappers::MPI::Vector &
      rotation_field() const
      {
        return rotation;
      }

      /** Timer of this scene's stages (a time scheme adds its own). */
      dealii::TimerOutput &
      timer()
      {
        return timing;
      }

      /** Print the timing summary of this scene's stages (rank 0). */
      void
      print_timing() const
      {
        timing.print_summary();
      }

      /** The mesh's contact level: its finest cells' level above the
       * global refinements. */
      unsigned int
      contact_level() const;

    private:
      void
      make_grid(const mesh::MeshRequest &request);
      void
      setup_contact();
      void
      setup_system();
      /** Whether the states solve with CG and the plain-aggregation
       * hierarchy (the cost model's memory factor). */
      bool
      plain_amg() const;
      /** The cost model's inputs for this scene at @p n_dofs DoFs: one
       * state, no adaptive cycle, no error estimate. */
      CostInputs
      cost_inputs(dealii::types::global_dof_index n_dofs) const;
      /** Print the cost estimate of the scene (stage/cost_estimate.h) and
       * stop if it does not fit into the available memory. */
      void
      announce_cost() const;
      contact::ContactState
      solve_state(const double load);
      /** What the solves of one state cost, over its levels. */
      struct SolveCost
      {
        unsigned int  iterations = 0; ///< Active-set iterations.
        unsigned long linear     = 0; ///< Linear-solver iterations.
        unsigned int  setups     = 0; ///< Preconditioner set-ups.
        /** Add the cost of @p result. */
        void
        add(const contact::ContactState &result);
      };
      /** Solve for @p load on the current mesh, add the cost to @p cost,
       * and return the stage's state. */
      results::StageState
      solve_level(const double load, SolveCost &cost);
      /** The error estimate's coarser levels: coarsen the mesh's finest
       * contact level mesh::ErrorControl::coarser_levels times, solve
       * @p load on each level from the coarsest up (into @p coarser,
       * coarsest first), each warm-started from the one below, and refine
       * back to the mesh asked for (the active set the finest coarser
       * solution's). False if the mesh has too few contact levels above
       * its global refinements (nothing done) or if a coarser solve failed
       * (coarse_failure says why; the mesh and warm start are restored). */
      bool
      solve_coarser_levels(const double                      load,
                           std::vector<results::StageState> &coarser,
                           SolveCost                        &cost);
      /** The bulk level: refine once every cell that the contact levels
       * leave as they are (below the two finest levels: the global
       * refinement level and the graded halo around the contacts), solve
       * @p load there warm-started from the mesh's active set, and
       * coarsen back to the mesh asked for. The state on the
       * refined bulk, or false (nothing changed) if the refinement would
       * not fit into the memory available or the solve failed
       * (coarse_failure says why). */
      bool
      solve_bulk_level(const double         load,
                       results::StageState &bulk,
                       SolveCost           &cost);
      /** The bulk mesh's error of @p fine, solved for @p load on the mesh
       * now: from solve_bulk_level(), or none (the console says why). */
      std::optional<results::BulkError>
      measure_bulk_error(const double               load,
                         const results::StageState &fine,
                         SolveCost                 &cost);
      /** After Target accuracy's cycles: measure the bulk part again on
       * the mesh @p fine was solved on, and give @p fine its contact
       * levels' estimate (from the two coarser @p levels) plus that part. */
      void
      remeasure_bulk_error(const double                            load,
                           const std::vector<results::StageState> &levels,
                           results::StageState                    &fine,
                           SolveCost                              &cost);
      /** Coarsen every cell of the finest level; returns the parents
       * (now active) of the cells coarsened. */
      std::set<dealii::CellId>
      coarsen_finest_level();
      /** Refine the active cells @p cells once. */
      void
      refine_cells(const std::set<dealii::CellId> &cells);
      /** Whether solve() refines and solves again after cycle @p cycle:
       * the adaptive cycles, or the target accuracy not met by @p fine
       * (which has an estimate if @p have_coarse). */
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
       * to the active cells; if not, says so on the console and records
       * it in memory_stop, naming the refinement as @p what. The flags
       * must be prepared
       * (prepare_coarsening_and_refinement()). Why: in 3D one refinement
       * at every active node multiplied the seed case's DoFs by five
       * (1.5 M to 7.5 M), and the run was killed for memory with its
       * state lost. */
      bool
      refinement_fits(
        const std::string &what = "the next refinement at the contacts");
      /** Print whether @p s met `Mesh/Target accuracy` (if set). */
      void
      report_accuracy(const results::StageState &s) const;
      /** The finest level refine_at_contacts() may reach. */
      unsigned int
      level_cap() const;
      /** After the triangulation changed: DoFs, contact nodes, load,
       * rotation field, and the active set carried over from
       * @p snapshot. */
      void
      rebuild(const ActiveSetSnapshot<dim> &snapshot);
      void
      compute_rotation_field();
      /** First state: the nodes that the analytical model's rotation for
       * @p load closes, under `Contact/First active set = hertz` and torque
       * control only those within first_set_reach() of the contact
       * point. */
      void
      initialise_active_set(const double load);
      /** How far from a pin's unloaded contact point the first active set
       * reaches. */
      struct FirstSetReach
      {
        /** Angle of the contact point about the pin's centre [rad]. */
        double angle = 0;
        /** Arc on the pin [mm]: the Hertz half-width of the analytical
         * force plus half a node spacing, at least one spacing. */
        double arc = 0;
      };
      /** Per disc and pin (index disc * zp + pin): the reach of the first
       * active set from the analytical state @p analytical. */
      std::vector<FirstSetReach>
      first_set_reach(const results::StageState &analytical) const;
      /** Per disc and pin: force sums in the housing frame and moment. */
      void
      sum_pin_forces(std::vector<results::PinState> &pins) const;
      /** The rigid take-up rotation towards the side @p sign of the
       * exact geometry at the current crank angle [rad] (unsigned). */
      double
      takeup_rotation(const int sign) const;
      /** Per pin of @p s: arm (of unloaded pins), clearance, phase, contact
       * point, approach, contact and Hertz widths, Hertz stresses; adds
       * the pins' moments to the reaction torque. */
      void
      set_pin_geometry(results::StageState &s) const;
      /** Per disc and pin: the largest nodal contact pressure [MPa]. */
      void
      set_peak_pressures(std::vector<results::PinState> &pins) const;
      /** Half-width of the active contact of disc @p d on pin @p j [mm]. */
      double
      contact_halfwidth(const unsigned int      d,
                        const unsigned int      j,
                        const dealii::Point<2> &contact_point) const;
      /** Angle about pin @p j's centre of each slave node of disc @p d
       * that faces it, from the unloaded contact point @p contact_point
       * (in [-pi, pi]), with the active set's flag; in 3D one entry per
       * node, so an angle repeats once per axial node. */
      std::vector<std::pair<double, bool>>
      pair_node_angles(const unsigned int      d,
                       const unsigned int      j,
                       const dealii::Point<2> &contact_point) const;
      /** Spacing of the slave nodes of disc @p d along the flank at its
       * unloaded contact point with pin @p j: the smaller gap between the
       * node nearest the point and its neighbours, as an arc on the pin
       * [mm]; 0 if the pair has fewer than two nodes. */
      double
      flank_node_spacing(const unsigned int      d,
                         const unsigned int      j,
                         const dealii::Point<2> &contact_point) const;

      const StageSettings             settings;
      const MPI_Comm                  comm;
      const geometry::CycloidGeometry geo;
      const analytic::StageModel      model;
      /** Crank angle of the mesh [rad]. */
      const double psi_mesh;
      /** Crank angle of the discs' placement [rad]. */
      double                      psi;
      dealii::ConditionalOStream  pcout;
      mutable dealii::TimerOutput timing;
      /** The mesh: shared or distributed (`Mesh/Triangulation`). */
      std::unique_ptr<dealii::parallel::TriangulationBase<dim>> tria;
      std::unique_ptr<contact::PinModel<dim>>                   pin_model;
      std::unique_ptr<contact::ContactProblem<dim>>             contact;
      dealii::TrilinosWrappers::MPI::Vector                     rotation;
      bool                                                      warm = false;
      /** The load of the state the active set comes from. */
      double warm_load = 0;
      /** Why the current state's coarser level failed (empty: it did
       * not). */
      std::string coarse_failure;
      /** Why the current state stopped refining before its target (empty:
       * it did not stop for memory). */
      std::string memory_stop;
    };
  } // namespace stage
} // namespace cycloid

#endif

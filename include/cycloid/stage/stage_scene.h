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
#include <cycloid/results/stage_state.h>
#include <cycloid/stage/cost_estimate.h>
#include <cycloid/stage/state_builder.h>

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
      /** Subsection `Crank bearings` (the reduced model's; the FE scene
       * holds the crank holes rigidly). */
      support::CrankBearingParameters bearings;
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
      /** Print the FE cost line and stop if the FE solve would not fit
       * (announce_cost()). The reduced model's coarse scene does not solve
       * contact: its owner costs the condensation instead
       * (stage::estimate_reduced_cost()). */
      bool check_cost = true;

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

      /** Write the last state's fields as @p name.pvtu (and its pieces)
       * into the output directory; the run adds it to its record
       * (postprocess::SolutionRecord), which the scene does not know. */
      void
      output_results(const std::string &name);

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

      /** @name The mesh levels, for the error control (ErrorControlLoop)
       * @{ */

      /** The mesh, which the error control coarsens and refines; rebuild()
       * after every change. */
      dealii::parallel::TriangulationBase<dim> &
      triangulation()
      {
        return *tria;
      }

      /** Solve for @p load (as solve() takes it) on the current mesh, from
       * the current active set, and return the stage's state: one level
       * of the error control, without its estimate and cost totals. */
      results::StageState
      solve_level(const double load);

      /** After the triangulation changed: DoFs, contact nodes, load,
       * rotation field, and the active set carried over from
       * @p snapshot. */
      void
      rebuild(const ActiveSetSnapshot<dim> &snapshot);

      /** The memory a state of this scene at @p n_dofs DoFs needs, by the
       * cost model [bytes] (one state, no cycle, no estimate). */
      double
      memory_needed(const dealii::types::global_dof_index n_dofs) const;

      /** @} */

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
      /** The pin-state extraction at the discs' current placement. */
      StateBuilder<dim>
      state_builder() const;
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
    };
  } // namespace stage
} // namespace cycloid

#endif

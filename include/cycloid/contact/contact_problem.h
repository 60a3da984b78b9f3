#ifndef cycloid_contact_contact_problem_h
#define cycloid_contact_contact_problem_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria_base.h>
#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/contact/constraint_formulation.h>
#include <cycloid/contact/contact_schur.h>
#include <cycloid/contact/contact_types.h>
#include <cycloid/contact/surface_search.h>
#include <cycloid/elasticity/elasticity.h>
#include <cycloid/parameters/material.h>

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief Frictionless contact of elastic bodies against exact cylinders
     * by a primal-dual active set (semi-smooth Newton, Hueber-Wohlmuth),
     * dual mortar (default) or node-to-surface, on 1 or more MPI ranks.
     *
     * A facade over the rooms of the contact layer: SurfaceSearch (slave
     * nodes, master faces, projections, ties), a ConstraintFormulation
     * (Mortar or NodeToSurface, by ContactSettings::formulation),
     * ActiveSetSolver (the iteration of a load state) and write_vtu().
     *
     * The slave surface (e.g. the cycloid flanks) carries the contact
     * nodes: every support point of a Q_p face, so Q1 and Q2 work alike (the
     * tensor-product Q2 face weights are positive, unlike serendipity
     * elements). A node i has the initial gap g_i = |x_i - c| - R to its
     * nearest cylinder and the normal n_i = (x_i - c)/|x_i - c| (mortar:
     * its dual-basis average, see Formulation). An active node is held on
     * the surface by the affine constraint
     * @f[ n_i \cdot (u_i - u_M(P_i)) = -g_i , @f]
     * which eliminates the node's dominant normal component (step-41/42):
     * the matrix stays symmetric positive definite, so CG with AMG given
     * the rigid-body modes applies. For a deformable master, u_M(P_i) is
     * the master body's finite-element displacement at the projection P_i
     * of the node onto the cylinder (mortar: dual-basis weighted over the
     * slave faces; its DoFs are ghosted on every rank); for a rigid master
     * u_M = 0. Nodes constrained by hanging nodes are never active.
     *
     * Load: a set of DoFs moves by beta * g (e.g. a rigid rotation of
     * crank holes). For a fixed active set the solution is affine in beta,
     * u = u0 + beta u1, so two solves with one matrix give the generalised
     * reaction Q(beta) = sum g . f_int = Q0 + beta Q1 and the beta that
     * meets a target load (load control), or Q at a given beta (rotation
     * control).
     *
     * Update: lambda_i = n_i . f_int,i (the constraint's reaction, > 0 in
     * compression) and the gap after the solve; a node is active next if
     * lambda_i + c (-gap_i) > 0, which for an active node (gap 0) means
     * lambda_i > 0 and for an inactive one (lambda 0) gap_i < 0. The state
     * has converged when the set repeats and the equilibrium residual
     * |C^T f_int| / |f_int| is below the tolerance; a set seen before
     * (cycling) or the iteration limit ends the state with an error.
     */
    template <int dim>
    class ContactProblem
    {
    public:
      /** Bodies and materials; no DoFs yet. */
      ContactProblem(
        const dealii::parallel::TriangulationBase<dim> &triangulation,
        const unsigned int                              degree,
        const std::map<dealii::types::material_id, parameters::ElasticMaterial>
                              &materials,
        const ContactSettings &settings);

      /**
       * Describe the contact: nodes of @p slave_surface on the bodies
       * @p slave_bodies against the @p cylinders, which are deformable
       * bodies of the mesh if @p deformable_masters, else rigid.
       */
      void
      set_contact(const std::set<dealii::types::material_id> &slave_bodies,
                  const dealii::types::boundary_id            slave_surface,
                  const std::vector<MasterCylinder>          &cylinders,
                  const bool deformable_masters);

      /** Glue the nodes of @p surface of body @p body to the nearest
       * cylinder in every component (e.g. pins in housing grooves). */
      void
      set_ties(const dealii::types::material_id body,
               const dealii::types::boundary_id surface);

      /** After a mesh change: distribute DoFs, find slave and tied nodes
       * and their masters. The active set restarts empty. */
      void
      setup();

      /** DoFs held at zero (each rank at least those of the cells it holds;
       * only the locally relevant ones are kept). */
      void
      set_fixed_dofs(const std::vector<dealii::types::global_dof_index> &dofs);

      /** DoFs moved by beta * g_d (the load direction of each DoF). */
      void
      set_load(const std::map<dealii::types::global_dof_index, double> &g);

      /** Start the active set from the nodes for which @p predicate holds
       * (a warm start, e.g. from an analytical model). */
      void
      initialise_active_set(
        const std::function<bool(const SlaveNode<dim> &)> &predicate);

      /** The active set's node positions and flags, to carry a warm start
       * over a mesh change (see transfer_active_set()). */
      std::vector<std::pair<SlaveNode<dim>, bool>>
      active_set_snapshot() const;

      /** Warm start after a mesh change: a new node takes the flag of the
       * nearest old node of the same body and cylinder. */
      void
      transfer_active_set(
        const std::vector<std::pair<SlaveNode<dim>, bool>> &snapshot);

      /**
       * Assemble the operator of the bodies as every state holds them (the
       * fixed DoFs, the load DoFs at rest, the ties) without any contact
       * constraint: the operator a reduced model condenses onto the contact
       * points. The caller sets its right-hand sides
       * (elasticity_problem().set_right_hand_side()) and solves with
       * elasticity_problem().solve_set(0, ...); one preconditioner serves
       * them all.
       */
      void
      assemble_without_contact();
      /** Solve for the target generalised reaction (load control). */
      ContactState
      solve_load(const double target, const std::string &label);

      /** Solve for a given beta (rotation control). */
      ContactState
      solve_displacement(const double beta, const std::string &label);

      /**
       * Time the stages of every later solve in sections of @p timer
       * ("contact: constraints and assembly", "contact: preconditioner",
       * "contact: linear solves", "contact: active-set update", "contact:
       * residual and reactions"; see ActiveSetSolver). The stages are
       * collective: call it on every rank alike, with a timer that outlives
       * the solves. Without a call nothing is timed.
       */
      void
      set_timer(dealii::TimerOutput &timer);

      /**
       * Rigid placement of the slave bodies relative to the masters: slave
       * positions (and the quadrature points of the mortar weights) are
       * mapped by @p placement(body, x) before the gap, the normal and the
       * master coefficients are computed. Displacements stay in the mesh
       * axes. Used by transient runs, where the disc follows the crank while
       * its mesh stays at the initial crank angle. Takes effect with
       * update_geometry().
       */
      void
      set_placement(
        const std::function<dealii::Point<dim>(dealii::types::material_id,
                                               const dealii::Point<dim> &)>
          &placement);

      /**
       * Recompute the slave nodes (gaps, normals, master coefficients) for
       * the current placement, keeping the active set by DoF and the fixed
       * DoFs and load. The slave numbering may change.
       */
      void
      update_geometry();

      /** The time-discrete (effective) operator; see
       * elasticity::DynamicTerms. */
      void
      set_dynamic_terms(const elasticity::DynamicTerms &terms)
      {
        problem->set_dynamic_terms(terms);
      }

      /** Scale the stored slave reactions by @p factor (time schemes whose
       * multiplier spans two time levels report their step average). */
      void
      scale_reactions(const double factor)
      {
        for (auto &r : solution.reactions)
          r *= factor;
      }

      /** The DoFs that turn by beta and their unit-rotation displacement. */
      const std::map<dealii::types::global_dof_index, double> &
      load_pattern() const
      {
        return load;
      }

      /** The elasticity problem (for energies and mass products). */
      elasticity::LinearElasticity<dim> &
      elasticity_problem()
      {
        return *problem;
      }

      /** Slave nodes (the same on every rank). */
      const std::vector<SlaveNode<dim>> &
      slave_nodes() const
      {
        return slaves;
      }

      /** Tied nodes. */
      const std::vector<TiedNode<dim>> &
      tied_nodes() const
      {
        return ties;
      }

      /** Indices of the active slave nodes. */
      const std::set<unsigned int> &
      active_set() const
      {
        return solution.active;
      }

      /** CG's starts for the next states (ActiveSetSolver keeps them;
       * a checkpoint saves them, so that a resumed run repeats the
       * uninterrupted one). */
      std::vector<WarmStart> &
      warm_starts()
      {
        return solution.starts;
      }

      /** See the other overload. */
      const std::vector<WarmStart> &
      warm_starts() const
      {
        return solution.starts;
      }

      /** Start the next state from the active set @p active (indices of
       * this mesh's slave nodes, e.g. an earlier active_set()). */
      void
      restart_active_set(const std::set<unsigned int> &active)
      {
        solution.active = active;
      }

      /** Reaction of every slave node in the last state (force of the
       * master on the slave body, N; per unit thickness in 2D), on every
       * rank; zero at inactive nodes. */
      const std::vector<dealii::Tensor<1, dim>> &
      slave_reactions() const
      {
        return solution.reactions;
      }

      /** Gap of every slave node after the last state [mm], every rank. */
      const std::vector<double> &
      slave_gaps() const
      {
        return solution.gaps;
      }

      /** Displacement of the last state (with ghosts). */
      const dealii::TrilinosWrappers::MPI::Vector &
      displacement() const
      {
        return solution.displacement;
      }

      /** The elasticity problem (DoFs, mapping, support points). */
      const elasticity::LinearElasticity<dim> &
      elasticity() const
      {
        return *problem;
      }

      /**
       * Write the last state as NAME.pvtu (+ one .vtu per rank):
       * displacement, von Mises stress, contact pressure (MPa), active
       * flag and (3D) gap (um) of the slave nodes, body id and MPI rank; in
       * 2D plane strain. Collective.
       */
      void
      write_vtu(const std::string &directory, const std::string &name) const;

    private:
      /** The load state for the generalised reaction @p value
       * (@p load_control) or for beta = @p value. */
      ContactState
      solve_state(const bool         load_control,
                  const double       value,
                  const std::string &label);
      /** Collect the slave nodes and couple them to their masters by the
       * formulation. */
      void
      find_slave_nodes();
      /** Add the master DoFs of all slave and tied constraints to the
       * elasticity problem's relevant (ghost) set. On a distributed mesh
       * also fetch the hanging lines of those that hang (master_hanging)
       * and ghost their parents, onto which the slave lines condense. */
      void
      ghost_master_dofs();
      /** The slave DoFs and their master DoFs, which decide the pattern. */
      std::vector<dealii::types::global_dof_index>
      pattern_signature() const;
      /** Give the elasticity problem the pattern of every candidate active
       * (LinearElasticity::set_pattern_superset()). */
      void
      fix_pattern();
      /** Size the per-slave reactions (zero) and gaps (initial gaps) after
       * the slave nodes were (re)collected. */
      void
      reset_slave_results();
      /** The owned cells at the slave and load DoFs (the only DoFs whose
       * forces the solver reads), rebuilt when those DoFs change. */
      const typename elasticity::LinearElasticity<dim>::CellList &
      force_cells();

      const ContactSettings settings;
      const std::map<dealii::types::material_id, parameters::ElasticMaterial>
                                                         materials;
      std::unique_ptr<elasticity::LinearElasticity<dim>> problem;
      /** Geometry of the contact, on *problem (stable across moves of this
       * object, as it lives on the heap). */
      SurfaceSearch<dim>                                search;
      std::unique_ptr<const ConstraintFormulation<dim>> formulation;

      std::vector<SlaveNode<dim>>                       slaves;
      std::vector<TiedNode<dim>>                        ties;
      std::vector<dealii::types::global_dof_index>      fixed;
      std::map<dealii::types::global_dof_index, double> load;
      /** Distributed mesh: the hanging lines of the master DoFs, the same on
       * every rank (ghost_master_dofs()). */
      dealii::AffineConstraints<double> master_hanging;
      /** The active set and the last state's results. */
      ContactSolution<dim> solution;
      /** Timer of the solver's stages; null: none. */
      dealii::TimerOutput *timer = nullptr;
      /** The factorisation kept across states
       * (ContactSettings::schur_complement; null: none). */
      std::unique_ptr<ContactSchur<dim>> schur;
      /** pattern_signature() of the fixed pattern. */
      std::vector<dealii::types::global_dof_index> signature;
      /** The DoFs of force_cells() (sorted; empty: not built on this
       * mesh) and the cells. */
      std::vector<dealii::types::global_dof_index>         force_dofs;
      typename elasticity::LinearElasticity<dim>::CellList cells_at_forces;
    };
  } // namespace contact
} // namespace cycloid

#endif

#ifndef cycloid_contact_contact_problem_h
#define cycloid_contact_contact_problem_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/distributed/tria_base.h>
#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/elasticity/elasticity.h>
#include <cycloid/parameters/material.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief A master surface of the contact: an exact circular cylinder
     * with its axis parallel to z (a circle in 2D), e.g. a pin. Gaps are
     * measured to this exact surface, never to the facets of its mesh.
     */
    struct MasterCylinder
    {
      /** Axis position in the xy plane [mm]. */
      dealii::Point<2> centre;
      /** Radius [mm]. */
      double radius = 0;
      /** Material id of the cylinder's body (its mesh, if deformable). */
      dealii::types::material_id body = 0;
      /** Boundary id of the cylinder's surface in its mesh. */
      dealii::types::boundary_id surface = 0;
    };

    /**
     * @brief A slave node of the node-to-surface contact: a support point
     * of the slave surface, paired with its nearest master cylinder.
     */
    template <int dim>
    struct SlaveNode
    {
      /** Material id of the slave body. */
      dealii::types::material_id body = 0;
      /** Index of the master cylinder. */
      unsigned int cylinder = 0;
      /** DoF indices of the node's dim displacement components. */
      std::array<dealii::types::global_dof_index, dim> dofs;
      /** Reference position [mm]. */
      dealii::Point<dim> position;
      /** Normal of the cylinder at the closest point, from the cylinder
       * into the slave body (no z component): unit for node-to-surface,
       * the dual-basis average int psi_i n / w_i (length 1 - O(h^2)) for
       * mortar. */
      dealii::Tensor<1, dim> normal;
      /** Initial gap to the exact cylinder [mm]. */
      double gap0 = 0;
      /** Integral of the node's shape function over the slave surface
       * [mm^(dim-1)]: contact pressure = normal force / weight. */
      double weight = 0;
      /** Constrained by a hanging node: never active (step-42's rule). */
      bool hanging = false;
      /** Deformable master: n . u_master(P) = sum_i coefficient_i u_i with
       * P the projection of the node onto the cylinder. Empty for a rigid
       * master. */
      std::vector<dealii::types::global_dof_index> master_dofs;
      std::vector<double>                          master_coefficients;
    };

    /**
     * @brief A node glued to a master cylinder's surface in every
     * displacement component (e.g. a housing groove holding a pin):
     * u_node = u_master(P).
     */
    template <int dim>
    struct TiedNode
    {
      std::array<dealii::types::global_dof_index, dim>              dofs;
      std::array<std::vector<dealii::types::global_dof_index>, dim> masters;
      std::array<std::vector<double>, dim>                          weights;
    };

    /**
     * @brief Discretisation of the contact constraint of a slave node.
     *
     * - `node_to_surface`: collocation at the node, n_i . (u_i - u_M(P_i))
     *   = -g(x_i). Cheap, but on non-matching meshes the master's
     *   piecewise-polynomial surface makes the nodal pressures oscillate
     *   (it fails the contact patch test); measured in doc/contact.md.
     * - `mortar`: the master displacement weighted with the dual
     *   (biorthogonal) basis psi_i of the slave faces, as in Wohlmuth's
     *   dual mortar: int psi_i n . (u_s - u_M) ds, whose slave part is
     *   diagonal (w_i n_i . u_i, w_i = int phi_i), so the constraint keeps
     *   the one-node form with master coefficients int psi_i n phi_m ds /
     *   w_i (integrals by quadrature on the slave faces) and the weighted
     *   normal n_i = int psi_i n / w_i (action = reaction exactly). The
     *   initial gap stays the exact gap at the node: the dual-weighted gap
     *   int psi_i g / w_i is biased by -kappa h^2/6 for a node touching a
     *   cylinder (kappa: curvature of the gap function), 16 um on a 0.75 mm
     *   flank face, as large as the clearances of a modified profile
     *   (measured: it engaged the wrong pins on a coarse 3D mesh).
     */
    enum class Formulation
    {
      node_to_surface,
      mortar
    };

    /** @brief Settings of the active-set iteration and the linear solver. */
    struct ContactSettings
    {
      /** Discretisation of the constraint. */
      Formulation formulation = Formulation::mortar;
      /** Iteration limit of the active set per load state. */
      unsigned int max_iterations = 100;
      /** Nodes closer than this to a master surface are candidates [mm]. */
      double search_distance = 0.1;
      /** Linear solver. */
      elasticity::LinearSolver solver = elasticity::LinearSolver::cg_amg;
      /** Relative tolerance of CG. */
      double solver_tolerance = 1e-10;
      /** Largest accepted relative equilibrium residual |C^T f_int| /
       * |f_int| of a converged state. */
      double residual_tolerance = 1e-6;
    };

    /** @brief Result of one load state. */
    struct ContactState
    {
      /** Load parameter beta (rotation [rad] or displacement [mm]). */
      double beta = 0;
      /** Generalised reaction Q(beta) = Q0 + beta Q1 at beta. */
      double reaction = 0;
      /** dQ/dbeta of the final active set (tangent stiffness). */
      double tangent = 0;
      /** Active-set iterations. */
      unsigned int iterations = 0;
      /** CG iterations, summed over the state. */
      unsigned int linear_iterations = 0;
      /** Relative equilibrium residual of the converged state. */
      double residual = 0;
      /** Number of active slave nodes. */
      unsigned int n_active = 0;
    };

    /**
     * @brief Frictionless contact of elastic bodies against exact cylinders
     * by a primal-dual active set (semi-smooth Newton, Hueber-Wohlmuth),
     * node-to-surface, on 1 or more MPI ranks.
     *
     * The slave surface (e.g. the cycloid flanks) carries the contact
     * nodes: every support point of a Q_p face, so Q1 and Q2 work alike (the
     * tensor-product Q2 face weights are positive, unlike serendipity
     * elements). A node i has the initial gap g_i = |x_i - c| - R to its
     * nearest cylinder and the normal n_i = (x_i - c)/|x_i - c|. An active
     * node is held on the surface by the affine constraint
     * @f[ n_i \cdot (u_i - u_M(P_i)) = -g_i , @f]
     * which eliminates the node's dominant normal component (step-41/42):
     * the matrix stays symmetric positive definite, so CG with AMG given
     * the rigid-body modes applies. For a deformable master, u_M(P_i) is
     * the master body's finite-element displacement at the projection P_i
     * of the node onto the cylinder (its DoFs are ghosted on every rank);
     * for a rigid master u_M = 0. Nodes constrained by hanging nodes are
     * never active.
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

      /** DoFs held at zero (every rank gives the same list). */
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

      /** Solve for the target generalised reaction (load control). */
      ContactState
      solve_load(const double target, const std::string &label);

      /** Solve for a given beta (rotation control). */
      ContactState
      solve_displacement(const double beta, const std::string &label);

      /** Slave nodes (the same on every rank). */
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
        for (auto &r : reactions)
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
        return active;
      }

      /** Reaction of every slave node in the last state (force of the
       * master on the slave body, N; per unit thickness in 2D), on every
       * rank; zero at inactive nodes. */
      const std::vector<dealii::Tensor<1, dim>> &
      slave_reactions() const
      {
        return reactions;
      }

      /** Gap of every slave node after the last state [mm], every rank. */
      const std::vector<double> &
      slave_gaps() const
      {
        return gaps;
      }

      /** Displacement of the last state (with ghosts). */
      const dealii::TrilinosWrappers::MPI::Vector &
      displacement() const
      {
        return u_last;
      }

      /** The elasticity problem (DoFs, mapping, support points). */
      const elasticity::LinearElasticity<dim> &
      elasticity() const
      {
        return *problem;
      }

      /**
       * Write the last state as NAME.pvtu (+ one .vtu per rank):
       * displacement, von Mises stress, contact pressure (MPa) and active
       * flag of the slave nodes, body id and MPI rank; in 2D plane strain.
       */
      void
      write_vtu(const std::string &directory, const std::string &name) const;

    private:
      ContactState
      solve_state(const bool         load_control,
                  const double       value,
                  const std::string &label);
      void
      find_slave_nodes();
      void
      find_tied_nodes();
      /** Add the master DoFs of all slave and tied constraints to the
       * elasticity problem's relevant (ghost) set. */
      void
      ghost_master_dofs();
      /** Size the per-slave reactions (zero) and gaps (initial gaps) after
       * the slave nodes were (re)collected. */
      void
      reset_slave_results();
      /** Mortar: replace each slave node's gap and master coefficients by
       * their dual-basis weighted averages over the slave faces. */
      void
      weight_by_dual_basis();
      /** The cells of the cylinders' surfaces: (cell, face) per cylinder. */
      void
      collect_master_faces();
      /** Shape-function weights of the master body at P (the projection of
       * a node onto cylinder j), per displacement component. */
      bool
      master_weights(
        const unsigned int                                             j,
        const dealii::Point<dim>                                      &P,
        std::array<std::vector<dealii::types::global_dof_index>, dim> &dofs,
        std::array<std::vector<double>, dim> &weights) const;
      std::function<void(dealii::AffineConstraints<double> &)>
      constraints(const bool with_gaps, const double beta) const;
      double
      reaction(const dealii::TrilinosWrappers::MPI::Vector &f) const;

      const MPI_Comm        comm;
      const ContactSettings settings;
      const std::map<dealii::types::material_id, parameters::ElasticMaterial>
                                                         materials;
      std::unique_ptr<elasticity::LinearElasticity<dim>> problem;

      std::set<dealii::types::material_id> slave_bodies;
      dealii::types::boundary_id           slave_surface = 0;
      std::vector<MasterCylinder>          cylinders;
      bool                                 deformable_masters = false;
      bool                                 with_ties          = false;
      dealii::types::material_id           tied_body          = 0;
      dealii::types::boundary_id           tied_surface       = 0;

      std::vector<std::vector<
        std::pair<typename dealii::DoFHandler<dim>::active_cell_iterator,
                  unsigned int>>>
        master_faces;
      /** Per master face: centre angle, half angular width, z range. */
      std::vector<std::vector<std::array<double, 4>>>   master_boxes;
      std::vector<SlaveNode<dim>>                       slaves;
      std::vector<TiedNode<dim>>                        ties;
      std::vector<dealii::types::global_dof_index>      fixed;
      std::map<dealii::types::global_dof_index, double> load;
      std::set<unsigned int>                            active;

      std::vector<dealii::Tensor<1, dim>>   reactions;
      std::vector<double>                   gaps;
      dealii::TrilinosWrappers::MPI::Vector u_last;
      std::function<dealii::Point<dim>(dealii::types::material_id,
                                       const dealii::Point<dim> &)>
        placement;
    };
  } // namespace contact
} // namespace cycloid

#endif

#ifndef cycloid_contact_contact_types_h
#define cycloid_contact_contact_types_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/elasticity/elasticity.h>

#include <array>
#include <set>
#include <vector>

/**
 * @file
 * The data the rooms of the contact layer hand to each other (surface
 * search, constraint formulation, active-set solver, output) and that
 * ContactProblem shows its callers. Plain structs, no behaviour, so that
 * every room can include them without including the others.
 */

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
     * @brief A slave node of the contact: a support point of the slave
     * surface, paired with its nearest master cylinder. The constraint
     * formulation (see ConstraintFormulation) sets its normal and master
     * coefficients.
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
      /** The coefficients of master_dofs (see there). */
      std::vector<double> master_coefficients;
    };

    /**
     * @brief A node glued to a master cylinder's surface in every
     * displacement component (e.g. a housing groove holding a pin):
     * u_node = u_master(P).
     */
    template <int dim>
    struct TiedNode
    {
      /** DoF indices of the node's dim displacement components. */
      std::array<dealii::types::global_dof_index, dim> dofs;
      /** Per component: the master DoFs of u_master(P). */
      std::array<std::vector<dealii::types::global_dof_index>, dim> masters;
      /** Per component: the master shape-function values at P. */
      std::array<std::vector<double>, dim> weights;
    };

    /**
     * @brief Where the first load state's active set starts
     * (`Contact/First active set`).
     */
    enum class FirstActiveSet
    {
      /** The nodes the analytical rotation closes, within the Hertz
       * half-width of the analytical pin force (plus half a node
       * spacing). */
      hertz,
      /** Every node the analytical rotation closes. */
      overlap
    };

    /**
     * @brief Discretisation of the contact constraint of a slave node
     * (Contact/Formulation; create_formulation() builds the implementation
     * by the same names).
     *
     * - `mortar` (the default): the master displacement weighted with the
     *   dual (biorthogonal) basis psi_i of the slave faces, as in
     *   Wohlmuth's dual mortar: int psi_i n . (u_s - u_M) ds, whose slave
     *   part is diagonal (w_i n_i . u_i, w_i = int phi_i), so the constraint
     *   keeps the one-node form with master coefficients int psi_i n phi_m
     *   ds / w_i (integrals by quadrature on the slave faces) and the
     *   weighted normal n_i = int psi_i n / w_i (action = reaction exactly).
     *   The initial gap stays the exact gap at the node: the dual-weighted
     *   gap int psi_i g / w_i is biased by -kappa h^2/6 for a node touching
     *   a cylinder (kappa: curvature of the gap function), 16 um on a
     *   0.75 mm flank face, as large as the clearances of a modified
     *   profile (measured: it engaged the wrong pins on a coarse 3D mesh).
     * - `node_to_surface` ("node-to-surface"): collocation at the node,
     *   n_i . (u_i - u_M(P_i)) = -g(x_i). Cheap, but on non-matching meshes
     *   the master's piecewise-polynomial surface makes the nodal pressures
     *   oscillate (it fails the contact patch test); measured in
     *   doc/contact.md.
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
      /** The factorisation of the direct solver. */
      elasticity::Factorisation factorisation =
        elasticity::Factorisation::cholmod;
      /** How ML builds the hierarchy of the CG solver. */
      elasticity::AMGHierarchy amg_hierarchy =
        elasticity::AMGHierarchy::smoothed_v;
      /** Relative tolerance of CG. */
      double solver_tolerance = 1e-10;
      /** Relative tolerance of CG of a state's first solve while the
       * active set still changes (the state's last iteration solves to
       * solver_tolerance). */
      double inner_tolerance = 1e-10;
      /** Keep one sparsity pattern and the AMG hierarchy over the active
       * sets, states and time steps of one mesh (rebuilt when the CG
       * iterations rise); false: a new pattern and hierarchy per set. */
      bool reuse_preconditioner = false;
      /** Largest accepted relative equilibrium residual |C^T f_int| /
       * |f_int| of a converged state. */
      double residual_tolerance = 1e-6;
      /** With the direct solver: keep one factorisation of the operator
       * with its supports over the sets, states and time steps, and solve
       * each set through the Schur complement of its contact rows
       * (ContactSchur); false: condense and factorise each set. */
      bool schur_complement = false;
      /** The most columns of the inverse the Schur complement keeps. */
      unsigned int schur_columns = 4000;
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
      /** Preconditioner set-ups (AMG hierarchies or direct factorisations)
       * of the state: one per active-set iteration, as each changes the
       * matrix. */
      unsigned int preconditioner_setups = 0;
      /** Active-set cycles broken by taking the union of the cycle's sets
       * (ActiveSetSolver, doc/stability.md \"Active-set cycling\"). */
      unsigned int cycles_broken = 0;
      /** The largest tension that a broken cycle's union left at a node,
       * over the largest nodal contact force [-]. */
      double cycle_tension = 0;
    };

    /**
     * @brief A state's two solutions u0 (gaps, no load) and u1 (unit load)
     * under one effective operator, kept as CG's start for the next state
     * under the same operator.
     *
     * Why: over the time steps (and load states) of a mesh the operator
     * stays and the active set moves by a few nodes, so the last state's
     * u0 and u1 are close to the next ones; from zero, CG must first
     * build the whole field.
     */
    struct WarmStart
    {
      /** The operator's factors of K and M (elasticity::DynamicTerms). */
      double stiffness = 1;
      /** See stiffness. */
      double mass = 0;
      /** The solution for the first right-hand side (ghosted) [mm]. */
      dealii::TrilinosWrappers::MPI::Vector u0;
      /** The solution for the second right-hand side, the torque
       * superposition's (ghosted) [mm]. */
      dealii::TrilinosWrappers::MPI::Vector u1;
    };

    /**
     * @brief What a load state leaves behind: the active set (also the
     * warm start of the next state) and, per slave node and on every rank,
     * the reaction and gap, plus the displacement.
     */
    template <int dim>
    struct ContactSolution
    {
      /** Indices of the active slave nodes. */
      std::set<unsigned int> active;
      /** Force of the master on each slave node [N; per mm in 2D]; zero
       * at inactive nodes. */
      std::vector<dealii::Tensor<1, dim>> reactions;
      /** Gap of each slave node after the state [mm]. */
      std::vector<double> gaps;
      /** Displacement u0 + beta u1 (with ghosts) [mm]. */
      dealii::TrilinosWrappers::MPI::Vector displacement;
      /** The solutions of the last states under the last two operators
       * (a transient step and its projection), most recent first; cleared
       * with the mesh. */
      std::vector<WarmStart> starts;
    };
  } // namespace contact
} // namespace cycloid

#endif

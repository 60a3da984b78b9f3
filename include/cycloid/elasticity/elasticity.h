#ifndef cycloid_elasticity_elasticity_h
#define cycloid_elasticity_elasticity_h

#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/types.h>

#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/elasticity/direct_solver.h>
#include <cycloid/parameters/material.h>

#include <functional>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include <Epetra_MultiVector.h>

namespace cycloid
{
  namespace elasticity
  {
    /** @brief Linear solver of an elasticity system. */
    enum class LinearSolver
    {
      /** CG preconditioned with ML AMG given the rigid-body modes. */
      cg_amg,
      /** CG with ML AMG given only the translations (for studies: how
       * much the rotations matter). */
      cg_amg_translations_only,
      /** Direct sparse solver on the matrix gathered to rank 0: Cholesky
       * (CHOLMOD, SparseCholesky), or Amesos' KLU (LU) for a matrix that is
       * not symmetric positive definite. (Many right-hand sides of one
       * matrix: LinearElasticity::inverse_form() with any Factorisation.) */
      direct
    };

    /**
     * @brief How ML builds the AMG hierarchy of LinearSolver::cg_amg
     * (`Solver/AMG hierarchy`).
     */
    enum class AMGHierarchy
    {
      /** Smoothed aggregation and a V-cycle (ML's elasticity default). */
      smoothed_v,
      /** Plain (unsmoothed) aggregation and a W-cycle: the prolongator
       * keeps the tentative one's few entries a row, so the set-up skips
       * the matrix products that smoothing needs and the hierarchy is a
       * fraction of the size; the W-cycle wins back what plain
       * aggregation loses in convergence (doc/solver-reuse.md). */
      plain_w
    };

    /** Whether @p solver is a direct (factorising) solver. */
    inline bool
    is_direct(const LinearSolver solver)
    {
      return solver == LinearSolver::direct;
    }

    /**
     * @brief Terms of a time-discrete (effective) operator: the matrix
     * becomes A = stiffness K + mass M (+ the inhomogeneities of the
     * constraints), and the first constraint set's right-hand side gains the
     * history load b = M w_M + K w_K. A Newmark or generalized-alpha step
     * with Rayleigh damping folds into these four terms (see
     * dynamics::ContactDynamics). Mass is consistent, from each body's
     * density.
     */
    struct DynamicTerms
    {
      /** Factor of K in A [-]. */
      double stiffness = 1.;
      /** Factor of M in A [1/s^2]. */
      double mass = 0.;
      /** w_M (ghosted; zero size: none) [mm/s^2]. */
      dealii::TrilinosWrappers::MPI::Vector mass_load;
      /** w_K (ghosted; zero size: none) [mm]. */
      dealii::TrilinosWrappers::MPI::Vector stiffness_load;
    };

    /** Lame parameters (lambda, mu) [MPa] of the isotropic material
     * @p m: lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)). */
    std::pair<double, double>
    lame_parameters(const parameters::ElasticMaterial &m);

    /**
     * @brief Small-strain linear elasticity of several bodies, each with its
     * own isotropic material (by material id), on a parallel triangulation:
     * Q_p elements, Trilinos matrices and vectors, CG with an algebraic
     * multigrid (ML) that is given the rigid-body modes (translations and
     * rotations) as its near-null space, or a direct solver.
     *
     * In 2D the problem is plane strain; forces are per unit thickness.
     *
     * The weak form is
     * @f[
     *  \sum_{\text{bodies}} \int_{\Omega_b} \varepsilon(v) :
     *   C_b : \varepsilon(u)\,dx = \int_{\Gamma_N} v \cdot t\,ds ,
     *  \qquad C_b = \lambda_b\, I\otimes I + 2\mu_b\, \mathbb{I}
     * @f]
     * with Dirichlet and other constraints supplied by the caller.
     */
    template <int dim>
    class LinearElasticity
    {
    public:
      /** Linear solver (see elasticity::LinearSolver). */
      using Solver = LinearSolver;
      /** A list of (locally owned, active) cells. */
      using CellList =
        std::vector<typename dealii::DoFHandler<dim>::active_cell_iterator>;

      /** @p materials maps each material id of the mesh to its material. */
      LinearElasticity(
        const dealii::parallel::TriangulationBase<dim> &triangulation,
        const unsigned int                              degree,
        const std::map<dealii::types::material_id, parameters::ElasticMaterial>
          &materials);

      /** DoFs to hold as ghosts on every rank in addition to the locally
       * relevant ones (e.g. the master DoFs that contact constraints of
       * this rank's slave nodes refer to). Takes effect at setup_system(). */
      void
      set_extra_relevant_dofs(
        const std::vector<dealii::types::global_dof_index> &extra)
      {
        extra_relevant = extra;
      }

      /** Distribute the DoFs (once per mesh) and compute the hanging-node
       * constraints of the cells this rank holds (see
       * hanging_node_constraints()). */
      void
      distribute_dofs();

      /**
       * Constraint sets of one structure (the same constrained DoFs and
       * entries, different inhomogeneities): the matrix and its sparsity
       * pattern follow the first set, right-hand side k the inhomogeneities
       * of set k. Each function adds its constraints to the hanging-node
       * constraints. Used by the contact solver: one matrix, one
       * preconditioner and two right-hand sides per active set.
       */
      void
      setup_constraints(
        const std::vector<
          std::function<void(dealii::AffineConstraints<double> &)>> &sets);

      /** How the next AMG set-ups build their hierarchy (default
       * AMGHierarchy::smoothed_v). */
      void
      set_amg_hierarchy(const AMGHierarchy hierarchy)
      {
        amg_hierarchy = hierarchy;
      }

      /** The factorisation of LinearSolver::direct (a Cholesky that
       * refuses a matrix hands it, and the rest of the run, to KLU). */
      void
      set_factorisation(const Factorisation f)
      {
        factorisation = f;
      }

      /**
       * Build, now, one sparsity pattern for every constraint set given to
       * setup_constraints() until the next call or distribute_dofs(): the
       * pattern has room for any set whose constrained DoFs and entries
       * are among those @p superset adds to the hanging-node constraints
       * (e.g. every contact candidate active), and the relevant DoFs are
       * those of this call (set_extra_relevant_dofs() before it). The
       * matrix is then built once, and the AMG hierarchy of an earlier
       * matrix on it stays in use (see setup_preconditioner()). Without a
       * call the pattern follows each set exactly. @p superset is not kept.
       */
      void
      set_pattern_superset(
        const std::function<void(dealii::AffineConstraints<double> &)>
          &superset);

      /**
       * Assemble the matrix with constraint set 0 and the right-hand side
       * of every set (tractions @p tractions, as in assemble(), plus the
       * inhomogeneities of each set).
       */
      void
      assemble_sets(const std::map<dealii::types::boundary_id,
                                   const dealii::Function<dim> *> &tractions);

      /**
       * Reassemble the right-hand side of constraint set 0 alone (the
       * history load of the dynamic terms), keeping the matrix and the
       * right-hand sides of the other sets; returns whether it did. It
       * does so only while the operator is the one the last
       * assemble_sets() built, without tractions: the same DoFs, the same
       * constraint sets and the same factors of K and M. Otherwise it
       * changes nothing and returns false, and the caller assembles.
       *
       * Why: a transient run through the contact Schur complement keeps
       * one operator for all its steps, and only the history load changes
       * from step to step; building the matrix is most of an assembly's
       * time.
       */
      bool
      assemble_history_load();

      /**
       * Build the preconditioner of the current matrix for @p solver (the
       * AMG hierarchy, or the factorisation of the direct solver) unless it
       * is built already; returns whether it built one. solve_set() calls
       * it itself: an explicit call moves the set-up out of the first solve
       * (e.g. to time it on its own).
       *
       * On a pattern fixed by set_pattern_superset(), an AMG hierarchy
       * built for earlier values of the matrix is kept: the matrices of
       * consecutive active sets, load states and time steps differ in a
       * few contact rows, so the old hierarchy still preconditions well and
       * CG's result does not depend on it. It is rebuilt when a solve needs
       * more than 1.5 times (plus 5) the iterations of the first solve after
       * the last build, or when CG fails with it. A mass operator (stiffness
       * factor 0, DynamicTerms) needs no hierarchy: solve_set() uses Jacobi
       * for it.
       */
      bool
      setup_preconditioner(const Solver solver);

      /** Preconditioners built so far (AMG hierarchies or factorisations;
       * not the Jacobi of mass operators), for the cost report. */
      unsigned int
      n_preconditioner_builds() const
      {
        return n_builds;
      }

      /**
       * Solve with the right-hand side of constraint set @p k and
       * distribute set k's constraints; @p u receives the solution with
       * ghosts (reinitialised). The preconditioner is built at the first
       * solve after an assembly (unless setup_preconditioner() built it)
       * and reused. Returns the number of CG
       * iterations (0 for direct). If @p u already holds a vector of the
       * right size (the previous active-set iteration's solution), CG starts
       * from it: the sets of consecutive iterations differ in a few contact
       * nodes, so the start is close and CG needs fewer iterations for the
       * same absolute tolerance (relative_tolerance times |rhs|).
       */
      unsigned int
      solve_set(const unsigned int                     k,
                const Solver                           solver,
                const double                           relative_tolerance,
                dealii::TrilinosWrappers::MPI::Vector &u);

      /**
       * The form R^T A^{-1} R of constraint set 0's matrix A and the
       * columns @p r (owned, condensed as for set_right_hand_side()): the
       * reduced model's compliance of its load cases, with one
       * factorisation of kind @p factorisation, kept for the next call
       * until the matrix is assembled again. Equals r_i^T u_j with u_j the
       * solution for r_j, set 0's (homogeneous) constraints distributed.
       * @p statistics, if given, receives the factorisation's
       * DirectSolver::statistics().
       */
      dealii::FullMatrix<double>
      inverse_form(const std::vector<dealii::TrilinosWrappers::MPI::Vector> &r,
                   const Factorisation factorisation,
                   std::string        *statistics = nullptr);

      /**
       * Replace the right-hand side of constraint set @p k by @p rhs (owned
       * entries, already condensed with that set's constraints, e.g. by
       * its distribute_local_to_global()), for loads that are not
       * tractions on a whole boundary id (the reduced model's contact
       * loads). Keeps the matrix and the preconditioner.
       */
      void
      set_right_hand_side(const unsigned int                           k,
                          const dealii::TrilinosWrappers::MPI::Vector &rhs)
      {
        rhs_sets.at(k) = rhs;
      }
      /**
       * Use the effective operator of @p terms from the next assemble_sets()
       * on (matrix, the first set's right-hand side, effective_forces() and
       * residual_norms()). Without a call the problem is static (A = K).
       */
      void
      set_dynamic_terms(const DynamicTerms &terms);

      /** The effective operator's terms (set_dynamic_terms()). */
      const DynamicTerms &
      dynamic_terms() const
      {
        return dynamic;
      }

      /** Back to the static operator A = K, b = 0. */
      void
      clear_dynamic_terms()
      {
        dynamic = DynamicTerms();
      }

      /**
       * Nodal forces of the effective operator, A u - b (with_load) or A u;
       * static problems: K u. Ghosted [N, per mm thickness in 2D]. With
       * @p cells, only their contributions are summed: the entries are
       * exact at the DoFs whose every cell is in the list (see
       * owned_cells_touching()) and partial elsewhere.
       */
      dealii::TrilinosWrappers::MPI::Vector
      effective_forces(const dealii::TrilinosWrappers::MPI::Vector &u,
                       const bool                                   with_load,
                       const CellList *cells = nullptr) const;

      /** The locally owned cells that hold at least one of @p dofs (any
       * order, repeats allowed): with them, effective_forces() is exact
       * at these DoFs, at the cost of a surface layer instead of the
       * mesh. */
      CellList
      owned_cells_touching(
        const std::vector<dealii::types::global_dof_index> &dofs) const;

      /**
       * Elastic energy u^T K u / 2 and kinetic energy v^T M v / 2 [N mm =
       * mJ; per mm thickness in 2D] of a displacement @p u [mm] and a
       * velocity @p v [mm/s] (both ghosted).
       */
      std::pair<double, double>
      energies(const dealii::TrilinosWrappers::MPI::Vector &u,
               const dealii::TrilinosWrappers::MPI::Vector &v) const;

      /** M x for a ghosted @p x, ghosted result [N]. */
      dealii::TrilinosWrappers::MPI::Vector
      mass_times(const dealii::TrilinosWrappers::MPI::Vector &x) const;

      /**
       * Equilibrium residual of @p u under constraint set @p k: the l2 norm
       * of C^T f_int(u) (internal forces condensed onto the unconstrained
       * DoFs, where equilibrium makes them vanish), and the l2 norm of
       * f_int(u) itself for scale.
       */
      std::pair<double, double>
      residual_norms(const dealii::TrilinosWrappers::MPI::Vector &u,
                     const unsigned int                           k) const;

      /**
       * The equilibrium residual of residual_norms(), condensed with
       * @p constraints (e.g. from make_constraints()) instead of a set of
       * setup_constraints(), with or without the history load
       * (@p with_load: the first set's right-hand side).
       */
      std::pair<double, double>
      residual_norms(const dealii::TrilinosWrappers::MPI::Vector &u,
                     const dealii::AffineConstraints<double>     &constraints,
                     const bool with_load) const;

      /** The closed constraints that setup_constraints() makes of @p set
       * (on the locally relevant DoFs, hanging nodes first), without
       * touching the matrix or the sets. */
      dealii::AffineConstraints<double>
      make_constraints(
        const std::function<void(dealii::AffineConstraints<double> &)> &set)
        const;

      /** The matrix of the last assemble_sets() (constraint set 0). */
      const dealii::TrilinosWrappers::SparseMatrix &
      matrix() const
      {
        return system_matrix;
      }

      /** The right-hand side of constraint set @p k (owned entries). */
      const dealii::TrilinosWrappers::MPI::Vector &
      right_hand_side(const unsigned int k) const
      {
        return rhs_sets.at(k);
      }

      /** Constraint set @p k of the last setup_constraints(). */
      const dealii::AffineConstraints<double> &
      constraint_set(const unsigned int k) const
      {
        return constraint_sets.at(k);
      }

      /** How many times the constraint sets were set up (or the DoFs
       * distributed, or the pattern fixed): unchanged, the sets of the last
       * setup_constraints() are still in place. */
      unsigned int
      n_constraint_setups() const
      {
        return constraint_setups;
      }

      /** The locally relevant DoFs again, with the extra ones given since
       * (what setup_constraints() does first), for a caller that keeps
       * the constraint sets in place. */
      void
      refresh_relevant_dofs()
      {
        if (!pattern_fixed)
          update_relevant_dofs();
      }

      /** How many times the DoFs were distributed: a change means that
       * every DoF-indexed quantity kept from before is void. */
      unsigned int
      n_distributions() const
      {
        return distributions;
      }

      /** Hanging-node constraints of every DoF of the cells this rank
       * holds: every DoF of the mesh on a shared triangulation (every rank
       * sees every cell), the locally relevant ones on a distributed one
       * (ContactProblem fetches those of far master DoFs from their
       * owners). */
      const dealii::AffineConstraints<double> &
      hanging_node_constraints() const
      {
        return hanging_all;
      }

      /** The finite element (dim components of FE_Q). */
      const dealii::FESystem<dim> &
      finite_element() const
      {
        return fe;
      }

      /** Distribute the DoFs and build the sparsity pattern. @p constrain
       * adds the problem's constraints (e.g. Dirichlet values) to the
       * hanging-node constraints; it is called with the constraint object
       * already initialised. */
      void
      setup_system(
        const std::function<void(dealii::AffineConstraints<double> &)>
          &constrain);

      /**
       * Assemble the stiffness matrix and the load vector with the
       * tractions @p tractions on the given boundary ids (each a function
       * with dim components, in force per area; per length in 2D).
       */
      void
      assemble(const std::map<dealii::types::boundary_id,
                              const dealii::Function<dim> *> &tractions);

      /**
       * Internal force vector f_int = sum_cells int B^T sigma(u) of a
       * displacement @p u (with ghosts), assembled without constraints: at
       * a constrained DoF it is the reaction of the constraint on the body,
       * at a free DoF (equilibrium, no load) zero. Returned with ghosts.
       */
      dealii::TrilinosWrappers::MPI::Vector
      internal_forces(const dealii::TrilinosWrappers::MPI::Vector &u) const;

      /** Locally owned DoFs. */
      const dealii::IndexSet &
      locally_owned_dofs() const
      {
        return locally_owned;
      }

      /** Locally relevant DoFs. */
      const dealii::IndexSet &
      locally_relevant_dofs() const
      {
        return locally_relevant;
      }

      /** Solve; returns the number of iterations (0 for direct). Throws
       * with the solver's message when it fails. */
      unsigned int
      solve(const Solver solver, const double relative_tolerance = 1e-10);

      /** The solution (with ghost entries). */
      const dealii::TrilinosWrappers::MPI::Vector &
      solution() const
      {
        return locally_relevant_solution;
      }

      /** The DoF handler. */
      const dealii::DoFHandler<dim> &
      dof_handler() const
      {
        return dofs;
      }

      /** The constraints (hanging nodes and the caller's). */
      const dealii::AffineConstraints<double> &
      constraints() const
      {
        return constraint_sets.at(0);
      }

      /** The mapping (of the same degree, following the manifolds). */
      const dealii::Mapping<dim> &
      mapping() const
      {
        return *map;
      }

      /** Number of degrees of freedom. */
      dealii::types::global_dof_index
      n_dofs() const
      {
        return dofs.n_dofs();
      }

      /** Whether every rank's rows come in blocks of dim, the components of
       * one support point in order (then, in 3D, ML aggregates nodes: "PDE
       * equations" = dim). Computed once per distribute_dofs(). Collective. */
      bool
      nodal_blocks() const;

      /**
       * Rigid-body modes of the locally owned DoFs, one column per mode
       * (dim translations, then dim(dim-1)/2 rotations about the origin),
       * on the row map of the system matrix.
       */
      std::unique_ptr<Epetra_MultiVector>
      rigid_body_modes(const bool with_rotations) const;

    private:
      /** The support point and vector component of every locally owned
       * DoF, by its row (index within the owned set). */
      void
      owned_support_points(std::vector<dealii::Point<dim>> &point,
                           std::vector<int>                &component) const;

      /** f += f_int(u) over the owned cells (those of @p cells if given);
       * with @p condense, also @p condensed += C^T f_int(u) (constrained
       * entries moved onto their masters); with @p operator_only, also the
       * forces without the history load added to it (the same loop). */
      void
      assemble_internal_forces(
        const dealii::TrilinosWrappers::MPI::Vector &u,
        dealii::TrilinosWrappers::MPI::Vector       &f,
        const dealii::AffineConstraints<double>     *condense,
        dealii::TrilinosWrappers::MPI::Vector       *condensed,
        const bool                                   effective = false,
        const bool                                   with_load = false,
        const CellList                              *cells     = nullptr,
        dealii::TrilinosWrappers::MPI::Vector *operator_only   = nullptr) const;

      /** Density of body @p m in t/mm^3 (the consistent unit with N, mm, s). */
      double
      density(const dealii::types::material_id m) const;

      DynamicTerms dynamic;

      const dealii::parallel::TriangulationBase<dim> &triangulation;
      const MPI_Comm                                  comm;
      const dealii::FESystem<dim>                     fe;
      std::unique_ptr<dealii::MappingQ<dim>>          map;
      dealii::DoFHandler<dim>                         dofs;
      const std::map<dealii::types::material_id, parameters::ElasticMaterial>
        materials;

      std::vector<dealii::types::global_dof_index>       extra_relevant;
      dealii::IndexSet                                   locally_owned;
      dealii::IndexSet                                   locally_relevant;
      dealii::AffineConstraints<double>                  hanging_all;
      std::vector<dealii::AffineConstraints<double>>     constraint_sets;
      dealii::TrilinosWrappers::SparseMatrix             system_matrix;
      std::vector<dealii::TrilinosWrappers::MPI::Vector> rhs_sets;
      dealii::TrilinosWrappers::MPI::Vector locally_relevant_solution;

      /** Rigid-body modes of the current DoFs (AMG's near-null space;
       * null until the first AMG set-up after distribute_dofs()). */
      std::unique_ptr<Epetra_MultiVector>       null_space;
      dealii::TrilinosWrappers::PreconditionAMG amg;
      /** Which preconditioner (if any) matches the current matrix:
       * stale_amg is the hierarchy of earlier values on the same pattern. */
      enum class Ready
      {
        none,
        amg,
        stale_amg,
        direct
      } ready = Ready::none;
      /** Whether the matrix holds a superset's pattern (kept by
       * setup_constraints()). */
      bool pattern_fixed = false;
      /** A solve asked for a new hierarchy (the iterations rose). */
      bool rebuild_amg = false;
      /** Aggregation and cycle of the AMG hierarchy. */
      AMGHierarchy amg_hierarchy = AMGHierarchy::smoothed_v;
      /** LinearSolver::direct's factorisation (set_factorisation()). */
      Factorisation factorisation = Factorisation::cholmod;
      /** CG iterations of the first solve after the last AMG build (0:
       * none yet). */
      unsigned int reference_iterations = 0;
      /** nodal_blocks() of the current DoFs (-1: not yet known). */
      mutable int blocked = -1;
      /** Preconditioners built so far. */
      unsigned int n_builds = 0;
      /** See n_distributions(). */
      unsigned int distributions = 0;
      /** See n_constraint_setups(). */
      unsigned int constraint_setups = 0;
      /** What the matrix holds, recorded by assemble_sets() and checked
       * by assemble_history_load(): the constraint set-up it was built
       * with and the factors of K and M (negative: nothing assembled, or
       * assembled with tractions). */
      struct AssembledOperator
      {
        /** n_constraint_setups() at the assembly. */
        unsigned int constraint_setups = 0;
        /** DynamicTerms::stiffness at the assembly. */
        double stiffness = -1.;
        /** DynamicTerms::mass at the assembly. */
        double mass = -1.;
      } assembled;
      /** structure_digest() of the set the exact pattern was built for. */
      std::size_t pattern_digest = 0;
      /** Jacobi preconditioner of a mass operator (stiffness factor 0). */
      dealii::TrilinosWrappers::PreconditionJacobi jacobi;
      /** Whether jacobi matches the current matrix. */
      bool jacobi_ready = false;

      /** The locally relevant DoFs with the extra ones. */
      void
      update_relevant_dofs();

      /** Free the matrix and every preconditioner built on it (before a
       * new pattern is built, so that the two never coexist). */
      void
      release_matrix();

      /** Reinitialise the matrix with the pattern of constraint set 0. */
      void
      build_exact_pattern();

      /** A digest of which DoFs @p c constrains onto which (not the
       * weights): the pattern it condenses the matrix into. */
      static std::size_t
      structure_digest(const dealii::AffineConstraints<double> &c);

      /** Distribute @p dsp over the ranks and reinitialise the matrix with
       * it (no preconditioner matches it then). */
      void
      reinit_matrix(dealii::DynamicSparsityPattern &dsp);

      /** Factorise the matrix with the chosen factorisation unless it
       * refused one before; whether it did (else the caller uses KLU). */
      bool
      try_factorisation();

      /** CG with the AMG on @p rhs from @p x, at most @p max_steps
       * iterations; returns the iterations or throws NoConvergence. */
      unsigned int
      run_cg(const dealii::TrilinosWrappers::MPI::Vector &rhs,
             const double                                 tolerance,
             const unsigned int                           max_steps,
             dealii::TrilinosWrappers::MPI::Vector       &x);
      /** LinearSolver::direct's factorisation: the chosen one (kept with
       * its symbolic analysis between matrices), or KLU once a matrix was
       * refused. */
      std::unique_ptr<DirectSolver> direct;
      /** Whether the chosen factorisation refused a matrix (then the run
       * uses KLU). */
      bool factorisation_refused = false;
      /** inverse_form()'s factorisation, kept for later calls while the
       * matrix stays (reset with it). */
      std::unique_ptr<DirectSolver> form_factor;
    };
  } // namespace elasticity
} // namespace cycloid

#endif

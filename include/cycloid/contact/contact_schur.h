#ifndef cycloid_contact_contact_schur_h
#define cycloid_contact_contact_schur_h

#include <deal.II/base/mpi.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/elasticity/elasticity.h>
#include <cycloid/elasticity/sparse_cholesky.h>

#include <functional>
#include <unordered_map>
#include <vector>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief The contact constraints of an active set solved through their
     * Schur complement on one kept factorisation of the operator with its
     * supports alone (`Solver/Contact Schur complement`).
     *
     * The active-set solver otherwise condenses each set's constraints
     * into the matrix and factorises it anew: two assemblies and two
     * factorisations a time step of the 2D transient example. But the
     * operator A (stiffness, mass, the supports, hanging nodes and ties)
     * is the same for every set and, at a fixed time step, for every step;
     * only the contact rows B u = g change. So A is factorised once, and
     * the solution of a set is that of the saddle-point problem
     *
     *     u = x + A^{-1} B^T mu,   (B A^{-1} B^T) mu = g - B x,
     *
     * with x the solution without contact. The entries of A^{-1} between
     * the DoFs that contact rows touch are computed once per DoF (unit
     * solves, four at a time) and kept while the factorisation is kept;
     * the dense Schur complement is small (one row per active node). Each
     * set then costs the dense solve and one back-substitution per
     * right-hand side instead of an assembly and a factorisation.
     *
     * What it gives is the condensed solution, to rounding: the same u0
     * (gaps, no load) and u1 (unit load) as the condensed path, from which
     * the active-set solver reads forces, gaps and the load exactly as
     * before.
     *
     * Requirements, checked: a direct Cholesky factorisation (SPD
     * operator; begin_state() returns false otherwise), and contact rows
     * that reach no inhomogeneous support (the load pattern).
     */
    template <int dim>
    class ContactSchur
    {
    public:
      /** A constraint function, as ActiveSetSolver builds them. */
      using Constraints =
        std::function<void(dealii::AffineConstraints<double> &)>;

      /** For the problems on the ranks of @p comm, keeping at most
       * @p max_columns columns of A^{-1} (8 max_columns^2 bytes on each
       * rank). Beyond it the least recently used are dropped down to half:
       * a long run moves its contacts along the flanks (the 2D example
       * keeps about 1500). */
      ContactSchur(const MPI_Comm comm, const std::size_t max_columns);

      /**
       * Assemble @p problem with the support sets @p supports (set 0: the
       * supports with no load, set 1: with the unit load; no contact
       * node), factorise it unless the matrix is the one factorised last
       * (then the kept entries of A^{-1} stay valid) and solve for both
       * right-hand sides (x0, x1). While the operator is the one
       * factorised (a time step at the same step size), only the history
       * load is assembled (LinearElasticity::assemble_history_load()).
       * Returns false, having done nothing else, if the matrix is not
       * symmetric positive definite.
       */
      bool
      begin_state(elasticity::LinearElasticity<dim> &problem,
                  const std::vector<Constraints>    &supports);

      /**
       * The two solutions of the active set whose contact lines
       * @p contact adds to the hanging nodes and the supports of set 0:
       * @p u0 with the gaps of the lines, @p u1 with the unit load and
       * zero gaps; both ghosted, as LinearElasticity::solve_set() leaves
       * them.
       */
      void
      solve_set(const elasticity::LinearElasticity<dim> &problem,
                const Constraints                       &contact,
                dealii::TrilinosWrappers::MPI::Vector   &u0,
                dealii::TrilinosWrappers::MPI::Vector   &u1);

      /** Factorisations computed so far. */
      unsigned int
      n_factorisations() const
      {
        return factor.n_factorisations();
      }

      /** DoFs whose column of A^{-1} is kept. */
      std::size_t
      n_columns() const
      {
        return dofs.size();
      }

      /** Columns computed in the last solve_set(). */
      std::size_t
      n_new_columns() const
      {
        return new_columns;
      }

      /** How many times the least recently used columns were dropped. */
      unsigned int
      n_evictions_so_far() const
      {
        return n_evictions;
      }

    private:
      /** One contact row: sum_j entries_j u_j = gap, over DoFs that no
       * support constrains. */
      struct Row
      {
        std::vector<std::pair<dealii::types::global_dof_index, double>> entries;
        double                                                          gap = 0;
      };

      /** The rows of the lines @p contact adds to the hanging nodes and
       * supports, with the constrained DoFs replaced by what holds them. */
      std::vector<Row>
      contact_rows(const Constraints &contact) const;

      /** Keep the columns of A^{-1} of every DoF of @p rows. */
      void
      add_columns(const std::vector<Row> &rows);

      /** Keep only the @p keep most recently used columns. */
      void
      evict(const std::size_t keep);

      /** Drop every kept column (a new operator or mesh). */
      void
      forget_columns();

      /** Entry (a, b) of A^{-1} between kept DoFs number a and b. */
      double
      inverse(const unsigned int a, const unsigned int b) const
      {
        return columns[b][a];
      }

      /** B A^{-1} B^T of @p rows, Cholesky-factorised (empty: none). */
      dealii::LAPACKFullMatrix<double>
      factorised_schur(const std::vector<Row> &rows) const;

      /** B x over the ranks, for @p x owned. */
      std::vector<double>
      row_products(const std::vector<Row>                      &rows,
                   const dealii::TrilinosWrappers::MPI::Vector &x) const;

      const std::size_t          max_columns;
      const MPI_Comm             comm;
      elasticity::SparseCholesky factor;
      /** The mesh (LinearElasticity::n_distributions()) of what is kept. */
      unsigned int distribution = 0;
      /** LinearElasticity::n_constraint_setups() after the supports were
       * set up. */
      unsigned int installed = 0;
      /** Whether the last begin_state() factorised the problem's matrix. */
      bool factored = false;
      /** Hanging nodes and supports (with the unit load) of every DoF,
       * as the contact lines find them (open) and closed. */
      dealii::AffineConstraints<double> open_held, held;
      /** The solutions without contact, owned entries. */
      dealii::TrilinosWrappers::MPI::Vector x0, x1;
      /** Kept DoFs and their numbers. */
      std::vector<dealii::types::global_dof_index>                  dofs;
      std::unordered_map<dealii::types::global_dof_index, unsigned> number;
      /** columns[b][a]: A^{-1} between kept DoFs a and b. */
      std::vector<std::vector<double>> columns;
      /** The set (count of solve_set() calls) that last used each. */
      std::vector<unsigned int> last_use;
      std::size_t               new_columns = 0;
      unsigned int              n_sets      = 0;
      unsigned int              n_evictions = 0;
    };
  } // namespace contact
} // namespace cycloid

#endif

#ifndef cycloid_elasticity_direct_solver_h
#define cycloid_elasticity_direct_solver_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <memory>
#include <string>
#include <vector>

namespace cycloid
{
  namespace elasticity
  {
    /**
     * @brief Which sparse factorisation a direct solve uses
     * (`Reduced/Direct solver`, and LinearSolver::direct's choice).
     *
     * The measurements behind each default are in doc/solver-reuse.md
     * ("One direct-solver interface").
     */
    enum class Factorisation
    {
      /** CHOLMOD L L^T, simplicial, AMD ordering, on the matrix gathered
       * to rank 0: the fastest for the 2D matrices of this project. */
      cholmod,
      /** CHOLMOD L L^T, supernodal (dense blocks through BLAS), METIS
       * ordering, gathered to rank 0: for 3D fill-in. */
      cholmod_supernodal,
      /** MUMPS L D L^T for a symmetric positive definite matrix, on every
       * rank (the lower triangle distributed as the matrix is). */
      mumps,
      /** MUMPS L U of the whole matrix (what Amesos_Mumps did before
       * issue #49): kept for the side-by-side measurement. */
      mumps_unsymmetric,
      /** Amesos' KLU (L U, gathered to rank 0): for a matrix that is not
       * symmetric positive definite. */
      klu
    };

    /** The prm name of @p f ("cholmod", "cholmod-supernodal", "mumps",
     * "mumps-unsymmetric", "klu"). */
    std::string
    to_string(const Factorisation f);

    /** The Factorisation named @p name (as to_string() writes it). */
    Factorisation
    factorisation_from_string(const std::string &name);

    /** The names of every Factorisation, "|"-separated (for a
     * Patterns::Selection). */
    std::string
    factorisation_names();

    /**
     * @brief Columns of distributed vectors gathered on rank 0 in the
     * global row order, and scattered back: the centralised right-hand
     * sides that CHOLMOD, KLU and MUMPS's host work on.
     */
    class RootColumns
    {
    public:
      /** The distribution: this rank owns the global rows @p my_rows (in
       * its local order) of a matrix of rows 0..n-1 over @p comm. */
      void
      reinit(const std::vector<int> &my_rows, const MPI_Comm comm);

      /** Number of rows (on rank 0; 0 elsewhere). */
      std::size_t
      n_rows() const
      {
        return rows.size();
      }

      /** Each rank's number of owned rows. */
      const std::vector<int> &
      counts() const
      {
        return owned_counts;
      }

      /** Global row of the k-th gathered row (rank 0). */
      const std::vector<int> &
      gathered_rows() const
      {
        return rows;
      }

      /** The vectors @p b on rank 0, column after column, each in the
       * global row order (n_rows() x b.size()); empty elsewhere. */
      std::vector<double>
      gather(const std::vector<const dealii::TrilinosWrappers::MPI::Vector *>
               &b) const;

      /** The inverse of gather(): rank 0's @p columns into @p x. */
      void
      scatter(
        const std::vector<double>                                  &columns,
        const std::vector<dealii::TrilinosWrappers::MPI::Vector *> &x) const;

    private:
      MPI_Comm         comm = MPI_COMM_SELF;
      std::vector<int> owned_counts, rows;
    };

    /**
     * @brief A sparse factorisation of a distributed matrix: factorise
     * once, solve many right-hand sides, entries of the inverse and the
     * form R^T A^{-1} R.
     *
     * One interface for every direct solve of the project (the time
     * stepping's Cholesky, the active-set Schur complement's entries of
     * the inverse, the reduced model's condensation), so that a
     * factorisation is chosen by name (make_direct_solver()) and measured
     * against the others on the same calls. All members are collective
     * over the matrix's communicator.
     */
    class DirectSolver
    {
    public:
      virtual ~DirectSolver() = default;

      /** Which factorisation this is. */
      virtual Factorisation
      kind() const = 0;

      /**
       * Factorise @p matrix. Returns false, on every rank, if this
       * factorisation cannot take it (a Cholesky of a matrix that is not
       * symmetric positive definite); failure() then says why.
       */
      virtual bool
      factorize(const dealii::TrilinosWrappers::SparseMatrix &matrix) = 0;

      /** Why the last factorize() refused the matrix (empty if not). */
      virtual const std::string &
      failure() const = 0;

      /** x_k = A^{-1} b_k for several right-hand sides at once (not
       * ghosted, the matrix's row distribution). */
      virtual void
      solve(const std::vector<dealii::TrilinosWrappers::MPI::Vector *>       &x,
            const std::vector<const dealii::TrilinosWrappers::MPI::Vector *> &b)
        const = 0;

      /** x = A^{-1} b. */
      void
      solve(dealii::TrilinosWrappers::MPI::Vector       &x,
            const dealii::TrilinosWrappers::MPI::Vector &b) const;

      /**
       * Entries of A^{-1}: the rows @p rows of the columns @p columns
       * (global indices), row-major (rows.size() x columns.size()), on
       * every rank. This default solves for the unit vectors, a few at a
       * time.
       */
      virtual std::vector<double>
      inverse_entries(
        const std::vector<dealii::types::global_dof_index> &columns,
        const std::vector<dealii::types::global_dof_index> &rows) const;

      /**
       * The symmetric form C = R^T A^{-1} R of the columns @p r (the
       * reduced model's compliance of its load cases), on every rank.
       * This default solves for the columns in blocks and takes the dot
       * products (symmetric to rounding, as computed: the caller can
       * measure the asymmetry); a Cholesky factorisation L L^T overrides
       * it with (L^{-1} R)^T (L^{-1} R), half the work of the solves and
       * symmetric by construction.
       */
      virtual dealii::FullMatrix<double>
      inverse_form(
        const std::vector<dealii::TrilinosWrappers::MPI::Vector> &r) const;

      /** One line on the last factorisation (entries of the factors,
       * memory), for progress output and the benchmarks. */
      virtual std::string
      statistics() const
      {
        return "";
      }

    protected:
      /** The rows of the last matrix factorised (for default members that
       * need vectors of its distribution). */
      void
      remember_rows(const dealii::TrilinosWrappers::SparseMatrix &matrix);

      /** This rank's rows of the last matrix factorised. */
      dealii::IndexSet owned_rows;
      /** The matrix's communicator. */
      MPI_Comm rows_comm = MPI_COMM_SELF;
    };

    /** A new, empty factorisation of kind @p f over @p comm. */
    std::unique_ptr<DirectSolver>
    make_direct_solver(const Factorisation f, const MPI_Comm comm);

    /** The rows this rank owns of @p matrix, as global indices in its local
     * order (RootColumns::reinit()'s input). */
    std::vector<int>
    owned_global_rows(const dealii::TrilinosWrappers::SparseMatrix &matrix);
  } // namespace elasticity
} // namespace cycloid

#endif

#ifndef cycloid_elasticity_sparse_cholesky_h
#define cycloid_elasticity_sparse_cholesky_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/elasticity/direct_solver.h>

#include <memory>
#include <string>
#include <vector>

namespace cycloid
{
  namespace elasticity
  {
    /**
     * @brief Sparse Cholesky factorisation A = L L^T of a distributed
     * symmetric positive definite Trilinos matrix: the matrix is gathered
     * to rank 0 and factorised there by CHOLMOD (SuiteSparse; simplicial
     * with AMD ordering, or supernodal with METIS ordering); each solve
     * gathers the right-hand side and scatters the solution back.
     *
     * Why not Amesos' KLU, which gathers the same way: KLU is an LU
     * factorisation made for circuit matrices, with no use of symmetry; on
     * the condensed Newmark matrix of the 2D transient example (139 k
     * DoFs) its factors hold twice the entries, and in the run it took
     * 0.54 s a factorisation and 0.05 s a solve against 0.24 s and
     * 0.035 s here, gathering included (doc/transient.md). The symbolic
     * analysis is kept while the sparsity pattern stays the same, and the
     * fill-reducing ordering while the fill it gives stays within 10 % of
     * a new ordering's: the contact constraints change a few hundred rows
     * of the pattern, not its shape.
     *
     * factorize() refuses (returns false on every rank) a matrix that is
     * not symmetric to rounding or not positive definite; the caller then
     * falls back to an LU factorisation.
     *
     * The supernodal variant is for 3D matrices, whose fill-in makes dense
     * blocks worth BLAS's level 3 (doc/solver-reuse.md, "One
     * direct-solver interface").
     */
    class SparseCholesky : public DirectSolver
    {
    public:
      /** A factorisation on the ranks of @p comm; supernodal with METIS
       * ordering if @p supernodal, else simplicial with AMD. */
      explicit SparseCholesky(const MPI_Comm comm,
                              const bool     supernodal = false);

      ~SparseCholesky() override;

      Factorisation
      kind() const override
      {
        return supernodal ? Factorisation::cholmod_supernodal :
                            Factorisation::cholmod;
      }

      /**
       * Factorise @p matrix. Returns false, on every rank, if it is not
       * symmetric (entries of A and A^T differing by more than 1e-10 of the
       * largest entry) or not positive definite; the reason is then
       * failure().
       */
      bool
      factorize(const dealii::TrilinosWrappers::SparseMatrix &matrix) override;

      using DirectSolver::solve;

      /** x_k = A^{-1} b_k for several right-hand sides at once (one
       * gather, one pass over the factor for up to four columns); @p x
       * and @p b with the matrix's row distribution (not ghosted). */
      void
      solve(const std::vector<dealii::TrilinosWrappers::MPI::Vector *>       &x,
            const std::vector<const dealii::TrilinosWrappers::MPI::Vector *> &b)
        const override;

      /** R^T A^{-1} R = Y^T Y with Y = L^{-1} P R: the forward solves
       * only, all columns as one block, and symmetric by construction. */
      dealii::FullMatrix<double>
      inverse_form(const std::vector<dealii::TrilinosWrappers::MPI::Vector> &r)
        const override;

      /** Entries of L and the factorisation's flops. */
      std::string
      statistics() const override;

      /**
       * Entries of A^{-1} for the last matrix factorize() accepted: the
       * rows @p rows of the columns @p columns (global indices), row-major
       * (rows.size() x columns.size()), on every rank. Rank 0 solves for
       * the unit vectors of the columns, four at a time (a solve of four
       * right-hand sides reads the factor once: 0.0075 s a column against
       * 0.017 s alone, 2D example's matrix).
       */
      std::vector<double>
      inverse_entries(
        const std::vector<dealii::types::global_dof_index> &columns,
        const std::vector<dealii::types::global_dof_index> &rows)
        const override;

      /** Whether the last factorize() found the matrix unchanged, entry by
       * entry, since the factorisation before, and kept that one. */
      bool
      kept_factor() const
      {
        return kept;
      }

      /** Factorisations computed so far (not counting kept ones). */
      unsigned int
      n_factorisations() const
      {
        return n_factors;
      }

      /** Whether the last factorize() reused the symbolic analysis (the
       * pattern was that of the factorisation before). */
      bool
      reused_analysis() const
      {
        return reused;
      }

      /** Why the last factorize() refused the matrix (empty if it did
       * not). */
      const std::string &
      failure() const override
      {
        return why;
      }

    private:
      /** Gather the rows of @p matrix to rank 0 (row_owner_offsets,
       * root_rows) and keep their lower triangle in compressed columns
       * there; an empty string if A is symmetric, else why not. */
      std::string
      gather_lower(const dealii::TrilinosWrappers::SparseMatrix &matrix);

      /** The gathered rows on rank 0 merged into the lower triangle;
       * empty string or why A is not symmetric. */
      std::string
      assemble_lower(const std::vector<int>    &row_start,
                     const std::vector<int>    &columns,
                     const std::vector<double> &entries);

      /** A digest of this rank's rows of @p matrix (indices and values),
       * the same on every rank as in the factorisation before iff the
       * matrix is the same. */
      static std::size_t
      fingerprint(const dealii::TrilinosWrappers::SparseMatrix &matrix);

      /** Factorise the gathered lower triangle on rank 0; the reason of a
       * failure (empty on success). */
      std::string
      factorize_on_root();

      const MPI_Comm comm;
      const bool     supernodal;
      /** CHOLMOD's workspace and factor (rank 0 only); its types stay out
       * of this header. */
      struct Cholmod;
      std::unique_ptr<Cholmod> cholmod;
      /** The rows' distribution (gathered to rank 0 and back). */
      RootColumns root;
      /** The gathered lower triangle (compressed columns, rank 0). */
      std::vector<int>    column_start, row_index;
      std::vector<double> values;
      bool                reused = false;
      /** Whether a factorisation is there (the last one was accepted). */
      bool        factorised = false;
      std::string why;
      /** fingerprint() of the factorised matrix, on each rank. */
      std::size_t  factored_digest = 0;
      bool         kept            = false;
      unsigned int n_factors       = 0;
    };
  } // namespace elasticity
} // namespace cycloid

#endif

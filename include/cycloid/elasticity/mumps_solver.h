#ifndef cycloid_elasticity_mumps_solver_h
#define cycloid_elasticity_mumps_solver_h

#include <cycloid/elasticity/direct_solver.h>

#include <memory>
#include <string>
#include <vector>

namespace cycloid
{
  namespace elasticity
  {
    /**
     * @brief MUMPS (the parallel multifrontal solver) on the distributed
     * matrix through its C interface: each rank hands MUMPS its own rows
     * (ICNTL(18) = 3); right-hand sides are centralised on rank 0 and
     * solved as one block.
     *
     * Why not Amesos_Mumps, which the project used before: it hands MUMPS
     * both triangles, so MUMPS can only be run unsymmetric (a symmetric
     * MUMPS sums a(i,j) and a(j,i)), and it solves the columns of a block
     * one at a time. In symmetric positive definite mode (sym = 1, L D L^T
     * without pivoting) MUMPS needs the lower triangle only and keeps half
     * the factor (doc/solver-reuse.md, "One direct-solver interface").
     */
    class MumpsSolver : public DirectSolver
    {
    public:
      /** A factorisation over @p comm: L D L^T of a symmetric positive
       * definite matrix if @p spd, else L U. */
      MumpsSolver(const MPI_Comm comm, const bool spd);

      ~MumpsSolver() override;

      Factorisation
      kind() const override
      {
        return spd ? Factorisation::mumps : Factorisation::mumps_unsymmetric;
      }

      /** Analyse (if the pattern changed) and factorise @p matrix; false,
       * with failure(), if MUMPS reports an error (a pivot that is not
       * positive in SPD mode, a singular matrix). */
      bool
      factorize(const dealii::TrilinosWrappers::SparseMatrix &matrix) override;

      const std::string &
      failure() const override
      {
        return why;
      }

      void
      solve(const std::vector<dealii::TrilinosWrappers::MPI::Vector *>       &x,
            const std::vector<const dealii::TrilinosWrappers::MPI::Vector *> &b)
        const override;

      /** R^T A^{-1} R: the columns of R solved as one block on rank 0, the
       * products with R over R's nonzero entries only (each load case
       * touches a few faces). */
      dealii::FullMatrix<double>
      inverse_form(const std::vector<dealii::TrilinosWrappers::MPI::Vector> &r)
        const override;

      /** Entries of the factors and MUMPS's memory (INFOG(29), (21)). */
      std::string
      statistics() const override;

    private:
      /** Solve the @p k columns of @p columns (rank 0's, n x k) in place;
       * collective. */
      void
      solve_on_root(std::vector<double> &columns, const std::size_t k) const;

      const MPI_Comm comm;
      const bool     spd;
      /** MUMPS's instance and the triplets it points to; its types stay out
       * of this header. */
      struct Mumps;
      std::unique_ptr<Mumps> mumps;
      RootColumns            root;
      std::string            why;
    };
  } // namespace elasticity
} // namespace cycloid

#endif

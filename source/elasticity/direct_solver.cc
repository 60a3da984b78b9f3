#include <deal.II/base/exceptions.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>

#include <cycloid/elasticity/direct_solver.h>
#include <cycloid/elasticity/mumps_solver.h>
#include <cycloid/elasticity/sparse_cholesky.h>

#include <algorithm>
#include <array>

#include <Epetra_CrsMatrix.h>
#include <Epetra_MultiVector.h>

namespace cycloid
{
  namespace elasticity
  {
    namespace
    {
      const std::array<std::pair<Factorisation, const char *>, 5> names = {
        {{Factorisation::cholmod, "cholmod"},
         {Factorisation::cholmod_supernodal, "cholmod-supernodal"},
         {Factorisation::mumps, "mumps"},
         {Factorisation::mumps_unsymmetric, "mumps-unsymmetric"},
         {Factorisation::klu, "klu"}}};
    } // namespace



    std::string
    to_string(const Factorisation f)
    {
      for (const auto &[kind, name] : names)
        if (kind == f)
          return name;
      return "?";
    }



    Factorisation
    factorisation_from_string(const std::string &name)
    {
      for (const auto &[kind, n] : names)
        if (name == n)
          return kind;
      AssertThrow(false,
                  dealii::ExcMessage("unknown direct solver '" + name +
                                     "' (one of " + factorisation_names() +
                                     ")"));
      return Factorisation::cholmod;
    }



    std::string
    factorisation_names()
    {
      std::string all;
      for (const auto &[kind, name] : names)
        all += (all.empty() ? "" : "|") + std::string(name);
      return all;
    }



    std::vector<int>
    owned_global_rows(const dealii::TrilinosWrappers::SparseMatrix &matrix)
    {
      const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
      std::vector<int>        rows(A.NumMyRows());
      for (int r = 0; r < A.NumMyRows(); ++r)
        rows[r] = A.GRID(r);
      return rows;
    }



    namespace
    {
      /**
       * @brief Where each rank's rows lie in a gather of k columns: each
       * rank sends its rows of every column in turn, so rank r's block
       * starts at offsets[r] * k.
       */
      struct BlockLayout
      {
        /** First gathered row of each rank (and the total, last). */
        std::vector<std::size_t> offsets;
        /** MPI's counts and displacements of the k-column blocks. */
        std::vector<int> counts, displs;

        BlockLayout(const std::vector<int> &owned_counts, const std::size_t k)
          : offsets(owned_counts.size() + 1, 0)
          , counts(owned_counts.size())
          , displs(owned_counts.size())
        {
          for (unsigned int r = 0; r < owned_counts.size(); ++r)
            {
              offsets[r + 1] = offsets[r] + owned_counts[r];
              counts[r]      = owned_counts[r] * k;
              displs[r]      = offsets[r] * k;
            }
        }

        /** Position of gathered row @p g of column @p c, rank @p r's, in
         * the gathered array. */
        std::size_t
        at(const unsigned int r, const std::size_t c, const std::size_t g) const
        {
          return displs[r] + c * (offsets[r + 1] - offsets[r]) +
                 (g - offsets[r]);
        }
      };
    } // namespace



    void
    RootColumns::reinit(const std::vector<int> &my_rows, const MPI_Comm c)
    {
      comm             = c;
      const int n_mine = my_rows.size();
      owned_counts.assign(dealii::Utilities::MPI::n_mpi_processes(comm), 0);
      MPI_Allgather(&n_mine, 1, MPI_INT, owned_counts.data(), 1, MPI_INT, comm);
      const BlockLayout layout(owned_counts, 1);
      const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      rows.assign(root ? layout.offsets.back() : 0, 0);
      MPI_Gatherv(my_rows.data(),
                  n_mine,
                  MPI_INT,
                  rows.data(),
                  layout.counts.data(),
                  layout.displs.data(),
                  MPI_INT,
                  0,
                  comm);
    }



    std::vector<double>
    RootColumns::gather(
      const std::vector<const dealii::TrilinosWrappers::MPI::Vector *> &b) const
    {
      const unsigned int  me = dealii::Utilities::MPI::this_mpi_process(comm);
      const int           my_rows = owned_counts[me];
      const std::size_t   k       = b.size();
      std::vector<double> local;
      local.reserve(my_rows * k);
      for (const auto *v : b)
        {
          const Epetra_MultiVector &bv = v->trilinos_vector();
          AssertThrow(bv.MyLength() == my_rows,
                      dealii::ExcMessage("direct solver: the vector's rows "
                                         "are not the matrix's"));
          local.insert(local.end(), bv[0], bv[0] + my_rows);
        }
      const BlockLayout   layout(owned_counts, k);
      const std::size_t   n = rows.size();
      std::vector<double> gathered(n * k);
      MPI_Gatherv(local.data(),
                  local.size(),
                  MPI_DOUBLE,
                  gathered.data(),
                  layout.counts.data(),
                  layout.displs.data(),
                  MPI_DOUBLE,
                  0,
                  comm);
      // Into the global row order, column after column.
      std::vector<double> ordered(n * k);
      for (unsigned int r = 0; r < owned_counts.size() && n > 0; ++r)
        for (std::size_t c = 0; c < k; ++c)
          for (std::size_t g = layout.offsets[r]; g < layout.offsets[r + 1];
               ++g)
            ordered[c * n + rows[g]] = gathered[layout.at(r, c, g)];
      return ordered;
    }



    void
    RootColumns::scatter(
      const std::vector<double>                                  &columns,
      const std::vector<dealii::TrilinosWrappers::MPI::Vector *> &x) const
    {
      const unsigned int  me = dealii::Utilities::MPI::this_mpi_process(comm);
      const int           my_rows = owned_counts[me];
      const std::size_t   k       = x.size();
      const std::size_t   n       = rows.size();
      const BlockLayout   layout(owned_counts, k);
      std::vector<double> solution(n * k);
      for (unsigned int r = 0; r < owned_counts.size() && n > 0; ++r)
        for (std::size_t c = 0; c < k; ++c)
          for (std::size_t g = layout.offsets[r]; g < layout.offsets[r + 1];
               ++g)
            solution[layout.at(r, c, g)] = columns[c * n + rows[g]];
      std::vector<double> mine(my_rows * k);
      MPI_Scatterv(solution.data(),
                   layout.counts.data(),
                   layout.displs.data(),
                   MPI_DOUBLE,
                   mine.data(),
                   mine.size(),
                   MPI_DOUBLE,
                   0,
                   comm);
      for (std::size_t c = 0; c < k; ++c)
        {
          Epetra_MultiVector &xv = x[c]->trilinos_vector();
          std::copy(mine.begin() + c * my_rows,
                    mine.begin() + (c + 1) * my_rows,
                    xv[0]);
        }
    }



    void
    DirectSolver::solve(dealii::TrilinosWrappers::MPI::Vector       &x,
                        const dealii::TrilinosWrappers::MPI::Vector &b) const
    {
      solve(std::vector<dealii::TrilinosWrappers::MPI::Vector *>{&x},
            std::vector<const dealii::TrilinosWrappers::MPI::Vector *>{&b});
    }



    void
    DirectSolver::remember_rows(
      const dealii::TrilinosWrappers::SparseMatrix &matrix)
    {
      owned_rows = matrix.locally_owned_range_indices();
      rows_comm  = matrix.get_mpi_communicator();
    }



    std::vector<double>
    DirectSolver::inverse_entries(
      const std::vector<dealii::types::global_dof_index> &columns,
      const std::vector<dealii::types::global_dof_index> &rows) const
    {
      using Vector           = dealii::TrilinosWrappers::MPI::Vector;
      const std::size_t   nr = rows.size(), nc = columns.size();
      std::vector<double> entries(nr * nc, 0.);
      const std::size_t   block = 4;
      for (std::size_t first = 0; first < nc; first += block)
        {
          const std::size_t   k = std::min(block, nc - first);
          std::vector<Vector> units(k, Vector(owned_rows, rows_comm)),
            x(k, Vector(owned_rows, rows_comm));
          std::vector<const Vector *> b;
          std::vector<Vector *>       xs;
          for (std::size_t j = 0; j < k; ++j)
            {
              if (owned_rows.is_element(columns[first + j]))
                units[j][columns[first + j]] = 1.;
              units[j].compress(dealii::VectorOperation::insert);
              b.push_back(&units[j]);
              xs.push_back(&x[j]);
            }
          solve(xs, b);
          for (std::size_t j = 0; j < k; ++j)
            for (std::size_t i = 0; i < nr; ++i)
              if (owned_rows.is_element(rows[i]))
                entries[i * nc + first + j] = x[j][rows[i]];
        }
      MPI_Allreduce(MPI_IN_PLACE,
                    entries.data(),
                    entries.size(),
                    MPI_DOUBLE,
                    MPI_SUM,
                    rows_comm);
      return entries;
    }



    dealii::FullMatrix<double>
    DirectSolver::inverse_form(
      const std::vector<dealii::TrilinosWrappers::MPI::Vector> &r) const
    {
      using Vector                 = dealii::TrilinosWrappers::MPI::Vector;
      const std::size_t          m = r.size();
      dealii::FullMatrix<double> form(m, m);
      const std::size_t          block = 16;
      for (std::size_t first = 0; first < m; first += block)
        {
          const std::size_t           k = std::min(block, m - first);
          std::vector<Vector>         x(k, Vector(owned_rows, rows_comm));
          std::vector<const Vector *> b;
          std::vector<Vector *>       xs;
          for (std::size_t j = 0; j < k; ++j)
            {
              b.push_back(&r[first + j]);
              xs.push_back(&x[j]);
            }
          solve(xs, b);
          for (std::size_t j = 0; j < k; ++j)
            for (std::size_t i = 0; i < m; ++i)
              form(i, first + j) = r[i] * x[j];
        }
      return form;
    }



    namespace
    {
      /**
       * @brief Amesos' KLU through deal.II's SolverDirect: the L U
       * factorisation for the matrices a Cholesky refuses.
       */
      class KluSolver : public DirectSolver
      {
      public:
        Factorisation
        kind() const override
        {
          return Factorisation::klu;
        }

        bool
        factorize(const dealii::TrilinosWrappers::SparseMatrix &matrix) override
        {
          remember_rows(matrix);
          control = std::make_unique<dealii::SolverControl>(1, 0);
          solver  = std::make_unique<dealii::TrilinosWrappers::SolverDirect>(
            *control,
            dealii::TrilinosWrappers::SolverDirect::AdditionalData(
              false, "Amesos_Klu"));
          solver->initialize(matrix);
          return true;
        }

        const std::string &
        failure() const override
        {
          return why;
        }

        void
        solve(const std::vector<dealii::TrilinosWrappers::MPI::Vector *> &x,
              const std::vector<const dealii::TrilinosWrappers::MPI::Vector *>
                &b) const override
        {
          AssertThrow(solver, dealii::ExcMessage("KLU: no factorisation"));
          for (unsigned int k = 0; k < x.size(); ++k)
            solver->solve(*x[k], *b[k]);
        }

      private:
        std::unique_ptr<dealii::SolverControl> control;
        /** SolverDirect::solve() is not const; the factor is not changed
         * by it. */
        mutable std::unique_ptr<dealii::TrilinosWrappers::SolverDirect> solver;
        std::string                                                     why;
      };
    } // namespace



    std::unique_ptr<DirectSolver>
    make_direct_solver(const Factorisation f, const MPI_Comm comm)
    {
      switch (f)
        {
          case Factorisation::cholmod:
            return std::make_unique<SparseCholesky>(comm, false);
          case Factorisation::cholmod_supernodal:
            return std::make_unique<SparseCholesky>(comm, true);
          case Factorisation::mumps:
            return std::make_unique<MumpsSolver>(comm, true);
          case Factorisation::mumps_unsymmetric:
            return std::make_unique<MumpsSolver>(comm, false);
          case Factorisation::klu:
            return std::make_unique<KluSolver>();
        }
      return nullptr;
    }
  } // namespace elasticity
} // namespace cycloid

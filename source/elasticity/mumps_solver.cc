#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>

#include <cycloid/elasticity/digest.h>
#include <cycloid/elasticity/mumps_solver.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <tuple>

#include <Epetra_CrsMatrix.h>
#include <Epetra_MultiVector.h>
#include <dmumps_c.h>

namespace cycloid
{
  namespace elasticity
  {
    /** MUMPS's instance, and the distributed triplets (1-based global
     * indices) it reads while it exists. */
    struct MumpsSolver::Mumps
    {
      DMUMPS_STRUC_C         id{};
      std::vector<MUMPS_INT> row, column;
      std::vector<double>    value;
      bool                   analysed = false;
      /** Digest of the pattern (row, column) of the last analysis. */
      std::size_t pattern = 0;
      /** Wall time of the last analysis, factorisation and solve [s]. */
      double seconds[3] = {0, 0, 0};

      Mumps(const MPI_Comm comm, const bool spd)
      {
        id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm));
        id.par          = 1; // the host works too
        id.sym          = spd ? 1 : 0;
        call(-1);
        // Quiet: the errors come back through INFOG(1) into failure().
        id.icntl[0] = -1;
        id.icntl[1] = -1;
        id.icntl[2] = -1;
        id.icntl[3] = 0;
        // The matrix distributed as given (each rank its own rows); the
        // right-hand sides dense and centralised, the solution on rank 0.
        id.icntl[17] = 3;
        id.icntl[19] = 0;
        id.icntl[20] = 0;
        // QAMD ordering: on the 3D seed case's coarse model (417 k DoFs,
        // several bodies) the analysis took 1.1 s against 5.0 s with
        // MUMPS's automatic choice (METIS), for 4 % fewer entries in the
        // factors (doc/solver-reuse.md).
        id.icntl[6] = 6;
      }

      void
      call(const int job)
      {
        const auto start = std::chrono::steady_clock::now();
        id.job           = job;
        dmumps_c(&id);
        if (job >= 1 && job <= 3)
          seconds[job - 1] = std::chrono::duration<double>(
                               std::chrono::steady_clock::now() - start)
                               .count();
      }

      /** MUMPS's error, or an empty string. */
      std::string
      error() const
      {
        if (id.infog[0] >= 0)
          return "";
        std::ostringstream s;
        s << "MUMPS error INFOG(1) = " << id.infog[0]
          << ", INFOG(2) = " << id.infog[1];
        if (id.infog[0] == -10 || id.infog[0] == -6)
          s << " (the matrix is singular or, in SPD mode, not positive "
               "definite)";
        if (id.infog[0] == -9 || id.infog[0] == -13)
          s << " (out of memory)";
        return s.str();
      }

      ~Mumps()
      {
        call(-2);
      }
    };



    MumpsSolver::MumpsSolver(const MPI_Comm comm, const bool spd)
      : comm(comm)
      , spd(spd)
      , mumps(std::make_unique<Mumps>(comm, spd))
    {}



    MumpsSolver::~MumpsSolver() = default;



    bool
    MumpsSolver::factorize(const dealii::TrilinosWrappers::SparseMatrix &matrix)
    {
      remember_rows(matrix);
      const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
      std::vector<MUMPS_INT>  row, column;
      std::vector<double>     value;
      for (int r = 0; r < A.NumMyRows(); ++r)
        {
          int     length = 0;
          double *v      = nullptr;
          int    *c      = nullptr;
          A.ExtractMyRowView(r, length, v, c);
          const int i = A.GRID(r);
          for (int k = 0; k < length; ++k)
            {
              const int j = A.GCID(c[k]);
              // SPD mode reads one triangle (it would add a(i,j) and
              // a(j,i)); stored zeros are left out as in SparseCholesky.
              if ((spd && j > i) || v[k] == 0.)
                continue;
              row.push_back(i + 1);
              column.push_back(j + 1);
              value.push_back(v[k]);
            }
        }
      root.reinit(owned_global_rows(matrix), comm);
      // The pattern's digest, not a copy of it, decides whether the last
      // analysis holds (the triplets go once factorised: memory).
      Digest digest;
      for (std::size_t k = 0; k < row.size(); ++k)
        {
          digest.add_word(row[k]);
          digest.add_word(column[k]);
        }
      const bool same_pattern =
        dealii::Utilities::MPI::min(
          static_cast<int>(mumps->analysed && digest.value() == mumps->pattern),
          comm) == 1;
      mumps->pattern = digest.value();
      mumps->row     = std::move(row);
      mumps->column  = std::move(column);
      mumps->value   = std::move(value);
      auto &id       = mumps->id;
      id.n           = matrix.m();
      id.nnz_loc     = mumps->row.size();
      id.irn_loc     = mumps->row.data();
      id.jcn_loc     = mumps->column.data();
      id.a_loc       = mumps->value.data();
      if (!same_pattern)
        {
          mumps->call(1);
          why             = mumps->error();
          mumps->analysed = why.empty();
          if (!why.empty())
            return false;
        }
      mumps->call(2);
      why = mumps->error();
      // SPD mode does not pivot: a matrix that is not positive definite
      // shows as negative pivots (INFOG(12)), not as an error.
      if (why.empty() && spd && mumps->id.infog[11] > 0)
        why = "the matrix is not positive definite (" +
              std::to_string(mumps->id.infog[11]) + " negative pivots)";
      // MUMPS holds its own copy now: the triplets' memory goes back before
      // the solves.
      mumps->row    = std::vector<MUMPS_INT>();
      mumps->column = std::vector<MUMPS_INT>();
      mumps->value  = std::vector<double>();
      id.irn_loc = id.jcn_loc = nullptr;
      id.a_loc                = nullptr;
      return why.empty();
    }



    void
    MumpsSolver::solve_on_root(std::vector<double> &columns,
                               const std::size_t    k) const
    {
      AssertThrow(why.empty() && mumps->analysed,
                  dealii::ExcMessage("MUMPS: no factorisation"));
      auto &id = mumps->id;
      id.nrhs  = k;
      id.lrhs  = id.n;
      id.rhs   = columns.data();
      mumps->call(3);
      id.rhs = nullptr;
      AssertThrow(id.infog[0] >= 0,
                  dealii::ExcMessage("MUMPS: the solve failed (" +
                                     mumps->error() + ")"));
    }



    void
    MumpsSolver::solve(
      const std::vector<dealii::TrilinosWrappers::MPI::Vector *>       &x,
      const std::vector<const dealii::TrilinosWrappers::MPI::Vector *> &b) const
    {
      AssertDimension(x.size(), b.size());
      std::vector<double> columns = root.gather(b);
      solve_on_root(columns, b.size());
      root.scatter(columns, x);
    }



    namespace
    {
      /**
       * @brief The columns of R in compressed columns (1-based rows, as
       * MUMPS reads them), the same on every rank.
       */
      struct SparseColumns
      {
        std::vector<MUMPS_INT> start, row;
        std::vector<double>    value;
      };

      /** R's nonzero entries, gathered from every rank and broadcast. */
      SparseColumns
      sparse_columns(
        const std::vector<dealii::TrilinosWrappers::MPI::Vector> &r,
        const MPI_Comm                                            comm)
      {
        // Each rank's entries as (column, row, value), in column order.
        std::vector<std::tuple<int, int, double>> mine;
        for (unsigned int j = 0; j < r.size(); ++j)
          {
            const auto &owned = r[j].locally_owned_elements();
            const auto &v     = r[j].trilinos_vector();
            for (int i = 0; i < v.MyLength(); ++i)
              if (v[0][i] != 0.)
                mine.emplace_back(j, owned.nth_index_in_set(i), v[0][i]);
          }
        auto all = dealii::Utilities::MPI::all_gather(comm, mine);
        std::vector<std::tuple<int, int, double>> entries;
        for (auto &part : all)
          entries.insert(entries.end(), part.begin(), part.end());
        std::sort(entries.begin(), entries.end());
        SparseColumns columns;
        columns.start.assign(r.size() + 1, 0);
        for (const auto &[j, i, v] : entries)
          {
            ++columns.start[j + 1];
            columns.row.push_back(i + 1);
            columns.value.push_back(v);
          }
        for (unsigned int j = 0; j < r.size(); ++j)
          columns.start[j + 1] += columns.start[j];
        for (auto &s : columns.start)
          ++s;
        return columns;
      }
    } // namespace



    dealii::FullMatrix<double>
    MumpsSolver::inverse_form(
      const std::vector<dealii::TrilinosWrappers::MPI::Vector> &r) const
    {
      AssertThrow(why.empty() && mumps->analysed,
                  dealii::ExcMessage("MUMPS: no factorisation"));
      const std::size_t m = r.size();
      // The load cases are sparse (a few faces each): MUMPS prunes the
      // forward elimination to the part of the tree they reach
      // (ICNTL(20) = 1), and leaves each rank the solution rows of its
      // fronts (ICNTL(21) = 1), so no dense block of n x m is gathered.
      SparseColumns rhs  = sparse_columns(r, comm);
      auto         &id   = mumps->id;
      const bool    root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      const MUMPS_INT        lsol = id.info[22];
      std::vector<double>    solution(static_cast<std::size_t>(lsol) * m);
      std::vector<MUMPS_INT> solution_rows(lsol);
      id.icntl[19]   = 1;
      id.icntl[20]   = 1;
      id.nrhs        = m;
      id.lrhs        = id.n;
      id.nz_rhs      = rhs.value.size();
      id.rhs_sparse  = root ? rhs.value.data() : nullptr;
      id.irhs_sparse = root ? rhs.row.data() : nullptr;
      id.irhs_ptr    = root ? rhs.start.data() : nullptr;
      id.lsol_loc    = lsol;
      id.sol_loc     = solution.data();
      id.isol_loc    = solution_rows.data();
      mumps->call(3);
      id.icntl[19]  = 0;
      id.icntl[20]  = 0;
      id.rhs_sparse = id.sol_loc = nullptr;
      id.irhs_sparse = id.irhs_ptr = id.isol_loc = nullptr;
      AssertThrow(id.infog[0] >= 0,
                  dealii::ExcMessage("MUMPS: the solve failed (" +
                                     mumps->error() + ")"));
      // C(i, j) = r_i . x_j over the rows this rank holds of x.
      std::vector<int> at(id.n, -1);
      for (MUMPS_INT k = 0; k < lsol; ++k)
        at[solution_rows[k] - 1] = k;
      dealii::FullMatrix<double> form(m, m);
      for (std::size_t i = 0; i < m; ++i)
        for (MUMPS_INT e = rhs.start[i] - 1; e < rhs.start[i + 1] - 1; ++e)
          if (const int k = at[rhs.row[e] - 1]; k >= 0)
            for (std::size_t j = 0; j < m; ++j)
              form(i, j) += rhs.value[e] * solution[j * lsol + k];
      dealii::Utilities::MPI::sum(form, comm, form);
      return form;
    }



    std::string
    MumpsSolver::statistics() const
    {
      const auto        &id = mumps->id;
      std::ostringstream s;
      // INFOG(29): entries of the factors (negative: in millions).
      const double entries =
        id.infog[28] < 0 ? -1e6 * id.infog[28] : 1. * id.infog[28];
      s << "MUMPS " << (spd ? "SPD (L D L^T)" : "unsymmetric (L U)") << ": "
        << entries << " entries in the factors, " << id.rinfog[2] << " flops, "
        << id.infog[21] << " MB used (all ranks); analysis "
        << mumps->seconds[0] << " s, factorisation " << mumps->seconds[1]
        << " s, last solve " << mumps->seconds[2] << " s";
      return s.str();
    }
  } // namespace elasticity
} // namespace cycloid

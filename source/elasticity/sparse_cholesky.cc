#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>

#include <cycloid/elasticity/digest.h>
#include <cycloid/elasticity/sparse_cholesky.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <Epetra_CrsMatrix.h>
#include <Epetra_MultiVector.h>
#include <suitesparse/cholmod.h>

namespace cycloid
{
  namespace elasticity
  {
    /** CHOLMOD's workspace, the factor, the pattern it was analysed for
     * and the last fill-reducing ordering with its fill. */
    struct SparseCholesky::Cholmod
    {
      const bool       supernodal;
      cholmod_common   common;
      cholmod_factor  *factor = nullptr;
      std::vector<int> column_start, row_index;
      std::vector<int> ordering;
      double           ordered_fill = 0;

      /** Supernodal (METIS) if @p supernodal, else simplicial (AMD). */
      explicit Cholmod(const bool supernodal)
        : supernodal(supernodal)
      {
        cholmod_start(&common);
        // Simplicial by default: with the reference BLAS that Debian's
        // deal.II links, the supernodal factorisation of the 2D example's
        // matrix took 0.30 s against 0.16 s (same fill, 2.1e8 flops).
        common.supernodal =
          supernodal ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
        // L L^T, not CHOLMOD's default L D L^T: only the former stops at a
        // pivot that is not positive, which is how an indefinite matrix is
        // recognised (same time on that matrix).
        common.final_ll = true;
        // The refusal is reported by factorize(), not printed by CHOLMOD.
        common.print = 0;
        use_ordering(false);
      }

      /** AMD alone (CHOLMOD's default also tries METIS when AMD's fill is
       * high; on the 2D example METIS gave more fill and took 0.5 s to
       * order against AMD's 0.07 s), or the kept ordering. */
      void
      use_ordering(const bool given)
      {
        // Nested dissection for the supernodal (3D) factorisations.
        common.nmethods           = 1;
        common.method[0].ordering = given      ? CHOLMOD_GIVEN :
                                    supernodal ? CHOLMOD_METIS :
                                                 CHOLMOD_AMD;
      }

      /** A new symbolic analysis of @p A: with the kept ordering if its
       * fill stays within 10 % of the fill it had when computed (that
       * skips AMD, half the analysis), else with a new one. */
      void
      analyse(cholmod_sparse &A)
      {
        if (factor != nullptr)
          cholmod_free_factor(&factor, &common);
        if (ordering.size() == A.nrow)
          {
            use_ordering(true);
            factor =
              cholmod_analyze_p(&A, ordering.data(), nullptr, 0, &common);
            if (factor != nullptr && common.lnz <= 1.1 * ordered_fill)
              return;
            if (factor != nullptr)
              cholmod_free_factor(&factor, &common);
          }
        use_ordering(false);
        factor = cholmod_analyze(&A, &common);
        if (factor == nullptr)
          return;
        const int *perm = static_cast<const int *>(factor->Perm);
        ordering.assign(perm, perm + A.nrow);
        ordered_fill = common.lnz;
      }

      /** Overwrite the @p k columns of length n in @p columns (column
       * after column) by A^{-1} times them. */
      void
      solve_in_place(std::vector<double> &columns, const std::size_t k)
      {
        apply_in_place({CHOLMOD_A}, columns, k);
      }

      /** Overwrite the @p k columns of @p columns by L^{-1} P times
       * them (the factor is L L^T: final_ll). */
      void
      forward_in_place(std::vector<double> &columns, const std::size_t k)
      {
        apply_in_place({CHOLMOD_P, CHOLMOD_L}, columns, k);
      }

      /** Apply CHOLMOD's solves @p systems (CHOLMOD_A, _P, _L, ...) in
       * turn to the @p k columns of @p columns, in place. */
      void
      apply_in_place(const std::vector<int> &systems,
                     std::vector<double>    &columns,
                     const std::size_t       k)
      {
        const std::size_t n = factor->n;
        cholmod_dense     B{};
        B.nrow           = n;
        B.ncol           = k;
        B.nzmax          = n * k;
        B.d              = n;
        B.x              = columns.data();
        B.xtype          = CHOLMOD_REAL;
        B.dtype          = CHOLMOD_DOUBLE;
        cholmod_dense *X = nullptr;
        for (const int system : systems)
          {
            cholmod_dense *Y =
              cholmod_solve(system, factor, X ? X : &B, &common);
            if (X)
              cholmod_free_dense(&X, &common);
            AssertThrow(Y != nullptr,
                        dealii::ExcMessage("SparseCholesky: the solve failed"));
            X = Y;
          }
        const double *xs = static_cast<const double *>(X->x);
        std::copy(xs, xs + n * k, columns.begin());
        cholmod_free_dense(&X, &common);
      }

      ~Cholmod()
      {
        if (factor != nullptr)
          cholmod_free_factor(&factor, &common);
        cholmod_finish(&common);
      }
    };



    SparseCholesky::SparseCholesky(const MPI_Comm comm, const bool supernodal)
      : comm(comm)
      , supernodal(supernodal)
    {
      if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        cholmod = std::make_unique<Cholmod>(supernodal);
    }



    SparseCholesky::~SparseCholesky() = default;



    bool
    SparseCholesky::factorize(
      const dealii::TrilinosWrappers::SparseMatrix &matrix)
    {
      // A time step with a kept active-set condensation (contact::
      // ContactSchur) assembles the same operator again: the digest finds
      // that, at the cost of one pass over the local rows.
      const std::size_t digest = fingerprint(matrix);
      const bool        same =
        dealii::Utilities::MPI::min(static_cast<int>(digest == factored_digest),
                                    comm) == 1;
      kept = same && why.empty() && factorised;
      if (kept)
        return true;
      why = gather_lower(matrix);
      if (why.empty() && cholmod)
        why = factorize_on_root();
      why             = dealii::Utilities::MPI::broadcast(comm, why, 0);
      reused          = dealii::Utilities::MPI::broadcast(comm, reused, 0);
      factored_digest = digest;
      ++n_factors;
      factorised = why.empty();
      return why.empty();
    }



    std::size_t
    SparseCholesky::fingerprint(
      const dealii::TrilinosWrappers::SparseMatrix &matrix)
    {
      // Every row's global indices and values, byte by byte.
      const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
      Digest                  digest;
      for (int r = 0; r < A.NumMyRows(); ++r)
        {
          int     length = 0;
          double *v      = nullptr;
          int    *c      = nullptr;
          A.ExtractMyRowView(r, length, v, c);
          const int row = A.GRID(r);
          digest.add_bytes(&row, sizeof(row));
          for (int k = 0; k < length; ++k)
            {
              const int column = A.GCID(c[k]);
              digest.add_bytes(&column, sizeof(column));
              digest.add_bytes(&v[k], sizeof(double));
            }
        }
      return digest.value();
    }



    namespace
    {
      /** Gather @p local (each rank's part, in rank order) on rank 0. */
      template <typename T>
      std::vector<T>
      gather_to_root(const std::vector<T> &local, const MPI_Comm comm)
      {
        const int        n = local.size();
        std::vector<int> counts(dealii::Utilities::MPI::n_mpi_processes(comm));
        MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
        std::vector<int> offsets(counts.size() + 1, 0);
        for (unsigned int r = 0; r < counts.size(); ++r)
          offsets[r + 1] = offsets[r] + counts[r];
        const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
        std::vector<T>     all(root ? offsets.back() : 0);
        const MPI_Datatype type =
          dealii::Utilities::MPI::internal::MPIDataTypes::mpi_type_id(
            local.data());
        MPI_Gatherv(local.data(),
                    n,
                    type,
                    all.data(),
                    counts.data(),
                    offsets.data(),
                    type,
                    0,
                    comm);
        return all;
      }

      /** Sort the entries [first, last) of a compressed column by row. */
      void
      sort_column(std::vector<int>    &index,
                  std::vector<double> &value,
                  const int            first,
                  const int            last)
      {
        bool sorted = true;
        for (int e = first + 1; e < last && sorted; ++e)
          sorted = index[e - 1] < index[e];
        if (sorted)
          return;
        std::vector<std::pair<int, double>> column;
        for (int e = first; e < last; ++e)
          column.emplace_back(index[e], value[e]);
        std::sort(column.begin(), column.end());
        for (int e = first; e < last; ++e)
          std::tie(index[e], value[e]) = column[e - first];
      }
    } // namespace



    std::string
    SparseCholesky::gather_lower(
      const dealii::TrilinosWrappers::SparseMatrix &matrix)
    {
      // Each rank's rows with global column indices (deal.II numbers the
      // rows 0 .. n-1 over the ranks).
      const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
      std::vector<int>        rows, lengths, columns;
      std::vector<double>     entries;
      for (int r = 0; r < A.NumMyRows(); ++r)
        {
          int     length = 0;
          double *v      = nullptr;
          int    *c      = nullptr;
          A.ExtractMyRowView(r, length, v, c);
          rows.push_back(A.GRID(r));
          // Stored zeros are left out: a pattern kept for every contact
          // candidate (Solver/Preconditioner reuse) would otherwise be
          // factorised in full.
          int kept = 0;
          for (int k = 0; k < length; ++k)
            if (v[k] != 0.)
              {
                columns.push_back(A.GCID(c[k]));
                entries.push_back(v[k]);
                ++kept;
              }
          lengths.push_back(kept);
        }
      root.reinit(rows, comm);
      const std::vector<int> &gathered_rows = root.gathered_rows();
      const std::vector<int>  all_len       = gather_to_root(lengths, comm);
      columns                               = gather_to_root(columns, comm);
      entries                               = gather_to_root(entries, comm);
      if (!cholmod)
        return "";
      // Row gathered_rows[k] starts at row_start[k] of the gathered arrays.
      const int        n = gathered_rows.size();
      std::vector<int> row_start(n + 1, 0);
      for (int k = 0; k < n; ++k)
        {
          AssertThrow(gathered_rows[k] >= 0 && gathered_rows[k] < n,
                      dealii::ExcMessage("SparseCholesky: rows not 0..n-1"));
          row_start[k + 1] = row_start[k] + all_len[k];
        }
      return assemble_lower(row_start, columns, entries);
    }



    std::string
    SparseCholesky::assemble_lower(const std::vector<int>    &row_start,
                                   const std::vector<int>    &columns,
                                   const std::vector<double> &entries)
    {
      // The upper triangle of row r, read as column r, is the lower
      // triangle of A^T; the lower triangle of the rows, transposed, is that
      // of A. Both are sorted into columns by counting; they must agree
      // (symmetry), and their mean is what is factorised.
      const std::vector<int> &gathered_rows = root.gathered_rows();
      const int               n             = gathered_rows.size();
      double                  largest       = 0;
      for (const double v : entries)
        largest = std::max(largest, std::abs(v));
      std::array<std::vector<int>, 2>    start, index;
      std::array<std::vector<double>, 2> value;
      for (unsigned int t = 0; t < 2; ++t)
        {
          // t = 0: entry (r, c) with c >= r goes to column r, row c;
          // t = 1: with c <= r, to column c, row r.
          const auto place = [&](const int r, const int c) {
            return t == 0 ? std::make_pair(r, c) : std::make_pair(c, r);
          };
          const auto keep = [&](const int r, const int c) {
            return t == 0 ? c >= r : c <= r;
          };
          start[t].assign(n + 1, 0);
          for (int k = 0; k < n; ++k)
            for (int e = row_start[k]; e < row_start[k + 1]; ++e)
              if (keep(gathered_rows[k], columns[e]))
                ++start[t][place(gathered_rows[k], columns[e]).first + 1];
          for (int j = 0; j < n; ++j)
            start[t][j + 1] += start[t][j];
          index[t].resize(start[t][n]);
          value[t].resize(start[t][n]);
          std::vector<int> next(start[t].begin(), start[t].end() - 1);
          for (int k = 0; k < n; ++k)
            for (int e = row_start[k]; e < row_start[k + 1]; ++e)
              if (keep(gathered_rows[k], columns[e]))
                {
                  const auto [j, i]   = place(gathered_rows[k], columns[e]);
                  index[t][next[j]]   = i;
                  value[t][next[j]++] = entries[e];
                }
          for (int j = 0; j < n; ++j)
            sort_column(index[t], value[t], start[t][j], start[t][j + 1]);
        }
      const double tolerance = 1e-10 * largest;
      column_start.assign(1, 0);
      row_index.clear();
      values.clear();
      for (int j = 0; j < n; ++j)
        {
          int a = start[0][j], b = start[1][j];
          // Merge the two sorted columns; a missing entry is a zero.
          while (a < start[0][j + 1] || b < start[1][j + 1])
            {
              const int    ra = a < start[0][j + 1] ? index[0][a] : n;
              const int    rb = b < start[1][j + 1] ? index[1][b] : n;
              const int    i  = std::min(ra, rb);
              const double va = ra == i ? value[0][a++] : 0.;
              const double vb = rb == i ? value[1][b++] : 0.;
              if (std::abs(va - vb) > tolerance)
                {
                  std::ostringstream s;
                  s << "the matrix is not symmetric (A(" << i << "," << j
                    << ") - A(" << j << "," << i << ") = " << vb - va
                    << ", largest entry " << largest << ")";
                  return s.str();
                }
              row_index.push_back(i);
              values.push_back(0.5 * (va + vb));
            }
          column_start.push_back(row_index.size());
        }
      return "";
    }



    std::string
    SparseCholesky::factorize_on_root()
    {
      cholmod_common &c = cholmod->common;
      cholmod_sparse  A{};
      A.nrow   = column_start.size() - 1;
      A.ncol   = A.nrow;
      A.nzmax  = row_index.size();
      A.p      = column_start.data();
      A.i      = row_index.data();
      A.x      = values.data();
      A.stype  = -1;
      A.itype  = CHOLMOD_INT;
      A.xtype  = CHOLMOD_REAL;
      A.dtype  = CHOLMOD_DOUBLE;
      A.sorted = 1;
      A.packed = 1;
      reused   = cholmod->factor != nullptr &&
               cholmod->column_start == column_start &&
               cholmod->row_index == row_index;
      if (!reused)
        {
          cholmod->analyse(A);
          if (cholmod->factor == nullptr)
            return "CHOLMOD's analysis failed (status " +
                   std::to_string(c.status) + ")";
          cholmod->column_start = column_start;
          cholmod->row_index    = row_index;
        }
      cholmod_factorize(&A, cholmod->factor, &c);
      if (c.status == CHOLMOD_NOT_POSDEF ||
          cholmod->factor->minor < cholmod->factor->n)
        return "the matrix is not positive definite (pivot " +
               std::to_string(cholmod->factor->minor) + ")";
      if (c.status != CHOLMOD_OK)
        return "CHOLMOD's factorisation failed (status " +
               std::to_string(c.status) + ")";
      return "";
    }



    void
    SparseCholesky::solve(
      const std::vector<dealii::TrilinosWrappers::MPI::Vector *>       &x,
      const std::vector<const dealii::TrilinosWrappers::MPI::Vector *> &b) const
    {
      AssertThrow(why.empty() && factorised,
                  dealii::ExcMessage("SparseCholesky: no factorisation"));
      AssertDimension(x.size(), b.size());
      // All right-hand sides in one gather, in the matrix's numbering.
      std::vector<double> columns = root.gather(b);
      if (cholmod)
        cholmod->solve_in_place(columns, b.size());
      root.scatter(columns, x);
    }



    dealii::FullMatrix<double>
    SparseCholesky::inverse_form(
      const std::vector<dealii::TrilinosWrappers::MPI::Vector> &r) const
    {
      AssertThrow(why.empty() && factorised,
                  dealii::ExcMessage("SparseCholesky: no factorisation"));
      const std::size_t                                          m = r.size();
      std::vector<const dealii::TrilinosWrappers::MPI::Vector *> b;
      for (const auto &v : r)
        b.push_back(&v);
      std::vector<double>        columns = root.gather(b);
      dealii::FullMatrix<double> form(m, m);
      if (cholmod)
        {
          const std::size_t n = cholmod->factor->n;
          cholmod->forward_in_place(columns, m);
          // Y^T Y, one triangle; a column's leading zeros (L^{-1} keeps
          // the entries above a load case's first row in the elimination
          // order zero) are skipped.
          std::vector<std::size_t> first(m, n);
          for (std::size_t i = 0; i < m; ++i)
            for (std::size_t k = 0; k < n && first[i] == n; ++k)
              if (columns[i * n + k] != 0.)
                first[i] = k;
          for (std::size_t i = 0; i < m; ++i)
            for (std::size_t j = 0; j <= i; ++j)
              {
                const double *yi = columns.data() + i * n;
                const double *yj = columns.data() + j * n;
                double        s  = 0;
                for (std::size_t k = std::max(first[i], first[j]); k < n; ++k)
                  s += yi[k] * yj[k];
                form(i, j) = form(j, i) = s;
              }
        }
      dealii::Utilities::MPI::sum(form, comm, form);
      return form;
    }



    std::string
    SparseCholesky::statistics() const
    {
      if (!cholmod || cholmod->factor == nullptr)
        return "";
      std::ostringstream s;
      s << "CHOLMOD " << (supernodal ? "supernodal" : "simplicial")
        << " L L^T: " << cholmod->common.lnz << " entries in L, "
        << cholmod->common.fl << " flops";
      return s.str();
    }



    std::vector<double>
    SparseCholesky::inverse_entries(
      const std::vector<dealii::types::global_dof_index> &columns,
      const std::vector<dealii::types::global_dof_index> &rows) const
    {
      AssertThrow(why.empty() && factorised,
                  dealii::ExcMessage("SparseCholesky: no factorisation"));
      const std::size_t   nr = rows.size(), nc = columns.size();
      std::vector<double> entries(nr * nc, 0.);
      if (cholmod)
        {
          const std::size_t   n     = cholmod->factor->n;
          const std::size_t   block = 4;
          std::vector<double> units(n * block);
          for (std::size_t first = 0; first < nc; first += block)
            {
              const std::size_t k = std::min(block, nc - first);
              std::fill(units.begin(), units.end(), 0.);
              for (std::size_t j = 0; j < k; ++j)
                {
                  AssertThrow(columns[first + j] < n,
                              dealii::ExcIndexRange(columns[first + j], 0, n));
                  units[j * n + columns[first + j]] = 1.;
                }
              cholmod->solve_in_place(units, k);
              for (std::size_t j = 0; j < k; ++j)
                for (std::size_t i = 0; i < nr; ++i)
                  entries[i * nc + first + j] = units[j * n + rows[i]];
            }
        }
      MPI_Bcast(entries.data(), entries.size(), MPI_DOUBLE, 0, comm);
      return entries;
    }
  } // namespace elasticity
} // namespace cycloid

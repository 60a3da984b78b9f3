// The sparse direct factorisations SuiteSparse offers, side by side on one
// matrix in MatrixMarket form (coordinate, real, both triangles): KLU (the
// LU that Amesos_Klu runs), UMFPACK, and CHOLMOD supernodal or simplicial
// with AMD or METIS, and simplicial with the previous ordering given (what
// elasticity::SparseCholesky does while the ordering's fill holds). One
// core, wall time of each phase; prints a markdown table.
//
// Build and run: see run.sh beside this file (doc/transient.md quotes the
// table).

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <suitesparse/cholmod.h>
#include <suitesparse/klu.h>
#include <suitesparse/umfpack.h>

namespace
{
  using Clock = std::chrono::steady_clock;

  double
  since(const Clock::time_point t)
  {
    return std::chrono::duration<double>(Clock::now() - t).count();
  }

  /** The matrix in compressed columns, rows sorted. */
  struct Csc
  {
    int                 n = 0;
    std::vector<int>    start, row;
    std::vector<double> value;
  };

  Csc
  read_matrix_market(const char *file)
  {
    std::ifstream in(file);
    std::string   line;
    while (std::getline(in, line) && line[0] == '%')
      ;
    long m, n, nnz;
    std::sscanf(line.c_str(), "%ld %ld %ld", &m, &n, &nnz);
    std::vector<std::pair<std::pair<int, int>, double>> entries(nnz);
    for (auto &e : entries)
      {
        in >> e.first.second >> e.first.first >> e.second; // (col, row)
        --e.first.first;
        --e.first.second;
      }
    std::sort(entries.begin(), entries.end());
    Csc a;
    a.n = n;
    a.start.assign(n + 1, 0);
    for (const auto &e : entries)
      {
        ++a.start[e.first.first + 1];
        a.row.push_back(e.first.second);
        a.value.push_back(e.second);
      }
    for (int j = 0; j < n; ++j)
      a.start[j + 1] += a.start[j];
    return a;
  }

  void
  print_row(const char  *name,
            const double analyse,
            const double factor,
            const double solve,
            const double entries)
  {
    std::printf("| %s | %.3f s | %.3f s | %.3f s | %.2f M |\n",
                name,
                analyse,
                factor,
                solve,
                entries / 1e6);
  }

  void
  run_klu(Csc &a)
  {
    klu_common c;
    klu_defaults(&c);
    auto          t  = Clock::now();
    klu_symbolic *S  = klu_analyze(a.n, a.start.data(), a.row.data(), &c);
    const double  ta = since(t);
    t                = Clock::now();
    klu_numeric *N =
      klu_factor(a.start.data(), a.row.data(), a.value.data(), S, &c);
    const double        tf = since(t);
    std::vector<double> x(a.n, 1.);
    t = Clock::now();
    klu_solve(S, N, a.n, 1, x.data(), &c);
    print_row("KLU", ta, tf, since(t), double(N->lnz) + N->unz);
    klu_free_numeric(&N, &c);
    klu_free_symbolic(&S, &c);
  }

  void
  run_umfpack(Csc &a)
  {
    void  *S, *N;
    double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
    umfpack_di_defaults(control);
    auto t = Clock::now();
    umfpack_di_symbolic(a.n,
                        a.n,
                        a.start.data(),
                        a.row.data(),
                        a.value.data(),
                        &S,
                        control,
                        info);
    const double ta = since(t);
    t               = Clock::now();
    umfpack_di_numeric(
      a.start.data(), a.row.data(), a.value.data(), S, &N, control, info);
    const double        tf = since(t);
    std::vector<double> b(a.n, 1.), x(a.n);
    t = Clock::now();
    umfpack_di_solve(UMFPACK_A,
                     a.start.data(),
                     a.row.data(),
                     a.value.data(),
                     x.data(),
                     b.data(),
                     N,
                     control,
                     info);
    print_row(
      "UMFPACK", ta, tf, since(t), info[UMFPACK_LNZ] + info[UMFPACK_UNZ]);
    umfpack_di_free_symbolic(&S);
    umfpack_di_free_numeric(&N);
  }

  /** CHOLMOD on the lower triangle; @p given: the ordering to reuse (empty:
   * CHOLMOD orders); returns the ordering it used. */
  std::vector<int>
  run_cholmod(const Csc              &a,
              const char             *name,
              const bool              supernodal,
              const int               ordering,
              const std::vector<int> &given)
  {
    cholmod_common c;
    cholmod_start(&c);
    c.supernodal         = supernodal ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
    c.final_ll           = true;
    c.nmethods           = 1;
    c.method[0].ordering = given.empty() ? ordering : CHOLMOD_GIVEN;
    std::vector<int>    start(1, 0), row;
    std::vector<double> value;
    for (int j = 0; j < a.n; ++j)
      {
        for (int k = a.start[j]; k < a.start[j + 1]; ++k)
          if (a.row[k] >= j)
            {
              row.push_back(a.row[k]);
              value.push_back(a.value[k]);
            }
        start.push_back(row.size());
      }
    cholmod_sparse A{};
    A.nrow = A.ncol = a.n;
    A.nzmax         = row.size();
    A.p             = start.data();
    A.i             = row.data();
    A.x             = value.data();
    A.stype         = -1;
    A.itype         = CHOLMOD_INT;
    A.xtype         = CHOLMOD_REAL;
    A.dtype         = CHOLMOD_DOUBLE;
    A.sorted = A.packed = 1;
    std::vector<int> perm(given);
    auto             t  = Clock::now();
    cholmod_factor  *L  = given.empty() ?
                            cholmod_analyze(&A, &c) :
                            cholmod_analyze_p(&A, perm.data(), nullptr, 0, &c);
    const double     ta = since(t);
    t                   = Clock::now();
    cholmod_factorize(&A, L, &c);
    const double   tf = since(t);
    cholmod_dense *B  = cholmod_ones(a.n, 1, CHOLMOD_REAL, &c);
    t                 = Clock::now();
    cholmod_dense *X  = cholmod_solve(CHOLMOD_A, L, B, &c);
    print_row(name, ta, tf, since(t), c.lnz);
    std::printf("    (%s: %.2e flops, status %d)\n", name, c.fl, c.status);
    const int       *p = static_cast<const int *>(L->Perm);
    std::vector<int> used(p, p + a.n);
    cholmod_free_dense(&X, &c);
    cholmod_free_dense(&B, &c);
    cholmod_free_factor(&L, &c);
    cholmod_finish(&c);
    return used;
  }
} // namespace

int
main(int argc, char **argv)
{
  if (argc != 2)
    {
      std::fprintf(stderr, "usage: %s MATRIX.mtx\n", argv[0]);
      return 1;
    }
  Csc a = read_matrix_market(argv[1]);
  std::printf("n %d, %zu entries\n\n", a.n, a.row.size());
  std::printf("| factorisation | analysis | numerical factorisation | one "
              "solve | entries of the factors |\n|---|---|---|---|---|\n");
  run_klu(a);
  run_umfpack(a);
  run_cholmod(a, "CHOLMOD supernodal, AMD", true, CHOLMOD_AMD, {});
  run_cholmod(a, "CHOLMOD supernodal, METIS", true, CHOLMOD_METIS, {});
  const auto amd =
    run_cholmod(a, "CHOLMOD simplicial, AMD", false, CHOLMOD_AMD, {});
  run_cholmod(a, "the same, the ordering given", false, CHOLMOD_AMD, amd);
  return 0;
}

// Linear elasticity against Lame's closed form: a thick cylinder (inner
// radius 0.2, outer 1.0, E = 1e9, nu = 0.2; the ring of doc/design-basis.md
// §2.3) under internal pressure in plane strain, on a quarter with symmetry
// conditions. Checks the displacement error and its convergence rate for Q1
// and Q2, the CG+AMG solution against the direct solver, and (run on 2 MPI
// ranks too) that the answer does not depend on the partition. Also: a
// matrix-sized block goes back to the system when it is freed, although a
// library linked in switches that off, and the freed small blocks' pages
// go back when asked (elasticity/heap.h).

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/vector_tools.h>

#include <cycloid/elasticity/direct_solver.h>
#include <cycloid/elasticity/elasticity.h>
#include <cycloid/elasticity/sparse_cholesky.h>
#include <cycloid/process/heap.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <memory>
#include <vector>

#include <malloc.h>

using namespace cycloid;

namespace
{
  constexpr double ri = 0.2, ro = 1.0, E = 1e9, nu = 0.2, p = 1e6;

  /** A 4 x 3 x 2 box of unit cells on a shared mesh (METIS partition). */
  std::unique_ptr<dealii::parallel::shared::Triangulation<3>>
  box_mesh()
  {
    auto tria = std::make_unique<dealii::parallel::shared::Triangulation<3>>(
      MPI_COMM_WORLD,
      dealii::Triangulation<3>::none,
      false,
      dealii::parallel::shared::Triangulation<3>::partition_metis);
    dealii::GridGenerator::subdivided_hyper_rectangle(
      *tria, {4, 3, 2}, dealii::Point<3>(), dealii::Point<3>(4, 3, 2));
    return tria;
  }

  /** Lame: u_r = (1+nu)/E ((1-2nu) A r + B / r), plane strain. */
  class Exact : public dealii::Function<2>
  {
  public:
    Exact()
      : dealii::Function<2>(2)
    {}
    void
    vector_value(const dealii::Point<2> &x,
                 dealii::Vector<double> &v) const override
    {
      const double A  = p * ri * ri / (ro * ro - ri * ri);
      const double B  = p * ri * ri * ro * ro / (ro * ro - ri * ri);
      const double r  = x.norm();
      const double ur = (1 + nu) / E * ((1 - 2 * nu) * A * r + B / r);
      v(0)            = ur * x[0] / r;
      v(1)            = ur * x[1] / r;
    }
  };

  /** Pressure on the inner surface: traction -p n, n the outer normal of
   * the body there, i.e. pointing to the axis: t = p x / r. */
  class InnerPressure : public dealii::Function<2>
  {
  public:
    InnerPressure()
      : dealii::Function<2>(2)
    {}
    void
    vector_value(const dealii::Point<2> &x,
                 dealii::Vector<double> &v) const override
    {
      v(0) = p * x[0] / x.norm();
      v(1) = p * x[1] / x.norm();
    }
  };

  struct Result
  {
    double       error;
    unsigned int iterations;
    double       u_inner;
  };

  Result
  solve(const unsigned int                            degree,
        const unsigned int                            refinements,
        const elasticity::LinearElasticity<2>::Solver solver)
  {
    dealii::parallel::shared::Triangulation<2> tria(
      MPI_COMM_WORLD,
      dealii::Triangulation<2>::none,
      false,
      dealii::parallel::shared::Triangulation<2>::partition_metis);
    dealii::GridGenerator::quarter_hyper_shell(
      tria, dealii::Point<2>(), ri, ro, 0, true);
    tria.refine_global(refinements);
    // Symmetry planes by geometry: x = 0 -> 2, y = 0 -> 3.
    for (const auto &cell : tria.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            const auto c = cell->face(f)->center();
            if (std::abs(c[0]) < 1e-12)
              cell->face(f)->set_boundary_id(2);
            else if (std::abs(c[1]) < 1e-12)
              cell->face(f)->set_boundary_id(3);
          }
    elasticity::LinearElasticity<2> problem(tria,
                                            degree,
                                            {{0, {E, nu, 7850.}}});
    problem.setup_system([&](dealii::AffineConstraints<double> &c) {
      const dealii::Functions::ZeroFunction<2> zero(2);
      dealii::VectorTools::interpolate_boundary_values(
        problem.mapping(),
        problem.dof_handler(),
        2,
        zero,
        c,
        dealii::ComponentMask(std::vector<bool>{true, false}));
      dealii::VectorTools::interpolate_boundary_values(
        problem.mapping(),
        problem.dof_handler(),
        3,
        zero,
        c,
        dealii::ComponentMask(std::vector<bool>{false, true}));
    });
    const InnerPressure pressure;
    problem.assemble({{0, &pressure}});
    Result result;
    result.iterations = problem.solve(solver, 1e-12);

    dealii::Vector<float> cell_errors(tria.n_active_cells());
    const Exact           exact;
    dealii::VectorTools::integrate_difference(problem.mapping(),
                                              problem.dof_handler(),
                                              problem.solution(),
                                              exact,
                                              cell_errors,
                                              dealii::QGauss<2>(degree + 2),
                                              dealii::VectorTools::L2_norm);
    result.error =
      dealii::VectorTools::compute_global_error(tria,
                                                cell_errors,
                                                dealii::VectorTools::L2_norm);
    // Radial displacement at the inner radius on the x axis.
    dealii::Vector<double> value(2);
    dealii::Vector<double> exact_value(2);
    exact.vector_value(dealii::Point<2>(ri, 0), exact_value);
    result.u_inner = exact_value(0);
    return result;
  }
} // namespace



TEST(Elasticity, LameCylinderConvergesAtTheOptimalRate)
{
  for (const unsigned int degree : {1u, 2u})
    {
      std::vector<double> errors;
      for (unsigned int level = 2; level <= 4; ++level)
        errors.push_back(
          solve(degree, level, elasticity::LinearElasticity<2>::Solver::cg_amg)
            .error);
      const double rate1 = std::log2(errors[0] / errors[1]);
      const double rate2 = std::log2(errors[1] / errors[2]);
      std::cout << "Q" << degree << " L2 errors " << errors[0] << ", "
                << errors[1] << ", " << errors[2] << "; rates " << rate1 << ", "
                << rate2 << std::endl;
      // L2 error of Q_p: O(h^(p+1)).
      EXPECT_GT(rate2, degree + 1 - 0.2);
      EXPECT_LT(rate2, degree + 1 + 0.3);
    }
  // And the error is small against the displacement itself: relative to
  // u(ri) sqrt(area of the quarter ring).
  const Result r = solve(2, 4, elasticity::LinearElasticity<2>::Solver::cg_amg);
  const double scale = r.u_inner * std::sqrt(0.25 * M_PI * (ro * ro - ri * ri));
  EXPECT_LT(r.error / scale, 1e-4);
}



TEST(Elasticity, AmgAndDirectSolversAgree)
{
  // Fine enough (about 2e4 DoFs) that ML builds a real hierarchy.
  const Result amg =
    solve(1, 6, elasticity::LinearElasticity<2>::Solver::cg_amg);
  const Result direct =
    solve(1, 6, elasticity::LinearElasticity<2>::Solver::direct);
  const Result translations =
    solve(1,
          6,
          elasticity::LinearElasticity<2>::Solver::cg_amg_translations_only);
  EXPECT_NEAR(amg.error, direct.error, 1e-6 * direct.error);
  EXPECT_NEAR(translations.error, direct.error, 1e-6 * direct.error);
  std::cout << "CG iterations with rigid-body modes " << amg.iterations
            << ", with translations only " << translations.iterations
            << std::endl;
  EXPECT_GT(amg.iterations, 1u);
  EXPECT_LT(amg.iterations, 60u);
}



TEST(Elasticity, RowsComeInNodalBlocksUnlessRenumbered)
{
  // ML aggregates whole nodes in 3D only if every rank's rows are the
  // components of one support point in order: deal.II's numbering of an
  // FESystem (Q1 and Q2) is, a component-wise renumbering is not.
  for (const unsigned int degree : {1u, 2u})
    for (const bool renumber : {false, true})
      {
        const auto                      tria = box_mesh();
        elasticity::LinearElasticity<3> problem(*tria,
                                                degree,
                                                {{0, {E, nu, 7850.}}});
        problem.setup_system([](dealii::AffineConstraints<double> &) {});
        if (renumber)
          dealii::DoFRenumbering::component_wise(
            const_cast<dealii::DoFHandler<3> &>(problem.dof_handler()));
        EXPECT_EQ(problem.nodal_blocks(), !renumber)
          << "degree " << degree << (renumber ? ", renumbered" : "");
      }
}



TEST(Elasticity, RigidBodyModesCostNoInternalForce)
{
  // The near-null space handed to ML: each translation and rotation,
  // evaluated at the support points of the owned DoFs, must be a
  // displacement without strain, so the internal forces of the free body
  // vanish. A mode built from wrong points (a node mixed up) strains the
  // body and fails this. Q1 and Q2, on 2 ranks.
  for (const unsigned int degree : {1u, 2u})
    {
      const auto                      tria = box_mesh();
      elasticity::LinearElasticity<3> problem(*tria,
                                              degree,
                                              {{0, {E, nu, 7850.}}});
      problem.setup_system([](dealii::AffineConstraints<double> &) {});
      const auto modes = problem.rigid_body_modes(true);
      ASSERT_EQ(modes->NumVectors(), 6);
      const auto &owned = problem.locally_owned_dofs();
      ASSERT_EQ(static_cast<std::size_t>(modes->MyLength()),
                owned.n_elements());
      // One field per column (-1: a shear u_y = x, the strained reference).
      const auto field = [&](const int k) {
        dealii::TrilinosWrappers::MPI::Vector o(owned, MPI_COMM_WORLD);
        for (unsigned int r = 0; r < owned.n_elements(); ++r)
          o[owned.nth_index_in_set(r)] =
            k >= 0 ? (*modes)[k][r] :
                     ((*modes)[1][r] == 1. ? (*modes)[3][r] : 0.);
        o.compress(dealii::VectorOperation::insert);
        dealii::TrilinosWrappers::MPI::Vector g(owned,
                                                problem.locally_relevant_dofs(),
                                                MPI_COMM_WORLD);
        g = o;
        // (A ghosted vector has no norm: sum the owned entries.)
        const auto f   = problem.internal_forces(g);
        double     sum = 0;
        for (const auto i : owned)
          sum += f[i] * f[i];
        return std::sqrt(dealii::Utilities::MPI::sum(sum, MPI_COMM_WORLD));
      };
      const double strained = field(-1);
      ASSERT_GT(strained, 0.);
      for (int k = 0; k < 6; ++k)
        EXPECT_LT(field(k), 1e-9 * strained)
          << "degree " << degree << ", mode " << k;
      // Every owned row carries exactly one unit translation.
      for (unsigned int r = 0; r < owned.n_elements(); ++r)
        EXPECT_EQ((*modes)[0][r] + (*modes)[1][r] + (*modes)[2][r], 1.)
          << "degree " << degree << ", row " << r;
    }
}



namespace
{
  /** A symmetric positive definite test matrix of size n on the ranks
   * (rows split evenly): 4 on the diagonal, -1 to the neighbours, -0.5 to
   * row i + n/3 (so that rows couple across the ranks and the columns come
   * unsorted into the gathered triangle), and a stored zero at (i, i + 2). */
  void
  fill_test_matrix(dealii::TrilinosWrappers::SparseMatrix &A,
                   const unsigned int                      n,
                   const double                            scale)
  {
    const auto comm = MPI_COMM_WORLD;
    const auto owned =
      dealii::Utilities::create_evenly_distributed_partitioning(
        dealii::Utilities::MPI::this_mpi_process(comm),
        dealii::Utilities::MPI::n_mpi_processes(comm),
        n);
    const auto entries = [&](const unsigned int i) {
      std::vector<std::pair<unsigned int, double>> e{{i, 4. * scale}};
      for (const int d : {-1, 1})
        if (i + d < n)
          e.push_back({i + d, -scale});
      for (const int d : {-int(n / 3), int(n / 3)})
        if (i + d < n)
          e.push_back({i + d, -0.5 * scale});
      for (const int d : {-2, 2})
        if (i + d < n)
          e.push_back({i + d, 0.});
      return e;
    };
    if (A.m() != n)
      {
        dealii::DynamicSparsityPattern dsp(n, n, owned);
        for (const auto i : owned)
          for (const auto &[j, v] : entries(i))
            dsp.add(i, j);
        A.reinit(owned, owned, dsp, comm);
      }
    for (const auto i : owned)
      for (const auto &[j, v] : entries(i))
        A.set(i, j, v);
    A.compress(dealii::VectorOperation::insert);
  }

  /** Largest error of the Cholesky solution of A x = A x_exact (x_exact_i
   * = sin i) over the ranks. */
  double
  cholesky_error(const elasticity::DirectSolver               &cholesky,
                 const dealii::TrilinosWrappers::SparseMatrix &A)
  {
    const auto                            comm = MPI_COMM_WORLD;
    dealii::TrilinosWrappers::MPI::Vector exact(A.locally_owned_range_indices(),
                                                comm),
      b(exact), x(exact);
    for (const auto i : A.locally_owned_range_indices())
      exact[i] = std::sin(double(i));
    exact.compress(dealii::VectorOperation::insert);
    A.vmult(b, exact);
    cholesky.solve(x, b);
    x -= exact;
    return x.linfty_norm();
  }
} // namespace



TEST(Elasticity, CholeskySolvesAndRefusesWhatItCannot)
{
  // A 2D-sized check of SparseCholesky (LinearSolver::direct), on 1 and 2
  // ranks: it must solve an SPD matrix to rounding, keep the analysis for
  // new values on the same pattern, and refuse (on every rank) a matrix
  // that is not symmetric or not positive definite instead of returning a
  // wrong answer.
  const unsigned int                     n = 301;
  dealii::TrilinosWrappers::SparseMatrix A;
  elasticity::SparseCholesky             cholesky(MPI_COMM_WORLD);
  fill_test_matrix(A, n, 1.);
  ASSERT_TRUE(cholesky.factorize(A)) << cholesky.failure();
  EXPECT_FALSE(cholesky.reused_analysis());
  EXPECT_LT(cholesky_error(cholesky, A), 1e-13);

  fill_test_matrix(A, n, 2.5);
  ASSERT_TRUE(cholesky.factorize(A)) << cholesky.failure();
  EXPECT_TRUE(cholesky.reused_analysis());
  EXPECT_LT(cholesky_error(cholesky, A), 1e-13);

  // One off-diagonal entry of the upper triangle changed: not symmetric.
  const auto owned = A.locally_owned_range_indices();
  if (owned.is_element(10))
    A.set(10, 11, -1.5);
  A.compress(dealii::VectorOperation::insert);
  EXPECT_FALSE(cholesky.factorize(A));
  EXPECT_NE(cholesky.failure().find("not symmetric"), std::string::npos)
    << cholesky.failure();

  // Symmetric again, with a negative diagonal entry: not positive definite.
  fill_test_matrix(A, n, 1.);
  if (owned.is_element(n / 2))
    A.set(n / 2, n / 2, -1.);
  A.compress(dealii::VectorOperation::insert);
  EXPECT_FALSE(cholesky.factorize(A));
  EXPECT_NE(cholesky.failure().find("not positive definite"), std::string::npos)
    << cholesky.failure();

  // And it recovers on a good matrix.
  fill_test_matrix(A, n, 1.);
  ASSERT_TRUE(cholesky.factorize(A)) << cholesky.failure();
  EXPECT_LT(cholesky_error(cholesky, A), 1e-13);
}



TEST(Elasticity, CholeskyKeepsItsFactorAndGivesEntriesOfTheInverse)
{
  // What contact::ContactSchur builds on, on 1 and 2 ranks: the same
  // matrix again keeps the factorisation, any changed value refactorises;
  // inverse_entries() are A^{-1}'s (A A^{-1} = I at the columns asked for,
  // symmetric); several right-hand sides in one solve give the single
  // solves' answers.
  const unsigned int                     n    = 301;
  const auto                             comm = MPI_COMM_WORLD;
  dealii::TrilinosWrappers::SparseMatrix A;
  elasticity::SparseCholesky             cholesky(comm);
  fill_test_matrix(A, n, 1.);
  ASSERT_TRUE(cholesky.factorize(A)) << cholesky.failure();
  EXPECT_FALSE(cholesky.kept_factor());
  ASSERT_TRUE(cholesky.factorize(A));
  EXPECT_TRUE(cholesky.kept_factor());
  EXPECT_EQ(cholesky.n_factorisations(), 1u);

  // Columns across both ranks' rows, all rows.
  const std::vector<dealii::types::global_dof_index> columns{
    0, 7, 150, 299, 300};
  std::vector<dealii::types::global_dof_index> rows(n);
  for (unsigned int i = 0; i < n; ++i)
    rows[i] = i;
  const std::vector<double> inverse = cholesky.inverse_entries(columns, rows);
  ASSERT_EQ(inverse.size(), n * columns.size());
  const auto owned          = A.locally_owned_range_indices();
  double     identity_error = 0, symmetry_error = 0;
  for (unsigned int c = 0; c < columns.size(); ++c)
    {
      dealii::TrilinosWrappers::MPI::Vector z(owned, comm), az(z);
      for (const auto i : owned)
        z[i] = inverse[i * columns.size() + c];
      z.compress(dealii::VectorOperation::insert);
      A.vmult(az, z);
      for (const auto i : owned)
        identity_error =
          std::max(identity_error,
                   std::abs(az[i] - (i == columns[c] ? 1. : 0.)));
      for (unsigned int d = 0; d < columns.size(); ++d)
        symmetry_error =
          std::max(symmetry_error,
                   std::abs(inverse[columns[d] * columns.size() + c] -
                            inverse[columns[c] * columns.size() + d]));
    }
  EXPECT_LT(dealii::Utilities::MPI::max(identity_error, comm), 1e-13);
  EXPECT_LT(symmetry_error, 1e-15);

  dealii::TrilinosWrappers::MPI::Vector b0(owned, comm), b1(b0), x0(b0), x1(b0),
    y0(b0), y1(b0);
  for (const auto i : owned)
    {
      b0[i] = std::sin(double(i));
      b1[i] = std::cos(3. * i);
    }
  b0.compress(dealii::VectorOperation::insert);
  b1.compress(dealii::VectorOperation::insert);
  cholesky.solve(x0, b0);
  cholesky.solve(x1, b1);
  cholesky.solve({&y0, &y1}, {&b0, &b1});
  y0 -= x0;
  y1 -= x1;
  EXPECT_LT(std::max(y0.linfty_norm(), y1.linfty_norm()), 1e-14);

  // One value changed (the pattern the same): a new factorisation.
  if (owned.is_element(n / 2))
    A.set(n / 2, n / 2, 4.5);
  A.compress(dealii::VectorOperation::insert);
  ASSERT_TRUE(cholesky.factorize(A));
  EXPECT_FALSE(cholesky.kept_factor());
  EXPECT_EQ(cholesky.n_factorisations(), 2u);
  EXPECT_LT(cholesky_error(cholesky, A), 1e-13);
}



TEST(Elasticity, EveryDirectSolverSolvesAndGivesTheFormOfTheInverse)
{
  // One interface, five factorisations (elasticity::DirectSolver), on 1
  // and 2 ranks. Each must solve to rounding, and give the form
  // R^T A^{-1} R of the reduced model's condensation; with R's columns
  // A's own columns c_j, the form is A(c_i, c_j) (R^T A^{-1} R = A), a
  // closed form that no solve enters. Entries of the inverse must agree
  // with A A^{-1} = I. The Cholesky kinds (CHOLMOD and MUMPS SPD) must
  // refuse a matrix that is not positive definite.
  const unsigned int                     n    = 301;
  const auto                             comm = MPI_COMM_WORLD;
  dealii::TrilinosWrappers::SparseMatrix A;
  fill_test_matrix(A, n, 1.);
  const auto owned = A.locally_owned_range_indices();
  // Columns on both ranks' rows, neighbours included (A(c_i, c_j) != 0).
  const std::vector<unsigned int> c{0, 1, 2, 100, 149, 150, 151, 250, 300};
  std::vector<dealii::TrilinosWrappers::MPI::Vector> R;
  for (const unsigned int j : c)
    {
      dealii::TrilinosWrappers::MPI::Vector e(owned, comm);
      R.emplace_back(owned, comm);
      if (owned.is_element(j))
        e[j] = 1.;
      e.compress(dealii::VectorOperation::insert);
      A.vmult(R.back(), e);
    }
  for (const auto kind : {elasticity::Factorisation::cholmod,
                          elasticity::Factorisation::cholmod_supernodal,
                          elasticity::Factorisation::mumps,
                          elasticity::Factorisation::mumps_unsymmetric,
                          elasticity::Factorisation::klu})
    {
      SCOPED_TRACE(elasticity::to_string(kind));
      auto solver = elasticity::make_direct_solver(kind, comm);
      ASSERT_EQ(solver->kind(), kind);
      fill_test_matrix(A, n, 1.);
      ASSERT_TRUE(solver->factorize(A)) << solver->failure();
      EXPECT_LT(cholesky_error(*solver, A), 1e-13);

      const dealii::FullMatrix<double> form = solver->inverse_form(R);
      // A.el() reads this rank's rows only: the largest over the ranks of
      // the rows each owns.
      double local = 0;
      for (unsigned int i = 0; i < c.size(); ++i)
        if (owned.is_element(c[i]))
          for (unsigned int j = 0; j < c.size(); ++j)
            local = std::max(local, std::abs(form(i, j) - A.el(c[i], c[j])));
      EXPECT_LT(dealii::Utilities::MPI::max(local, comm), 1e-12);

      const std::vector<dealii::types::global_dof_index> columns{3, 150, 299};
      std::vector<dealii::types::global_dof_index>       rows(n);
      for (unsigned int i = 0; i < n; ++i)
        rows[i] = i;
      const std::vector<double> inverse =
        solver->inverse_entries(columns, rows);
      double identity_error = 0;
      for (unsigned int k = 0; k < columns.size(); ++k)
        {
          dealii::TrilinosWrappers::MPI::Vector z(owned, comm), az(z);
          for (const auto i : owned)
            z[i] = inverse[i * columns.size() + k];
          z.compress(dealii::VectorOperation::insert);
          A.vmult(az, z);
          for (const auto i : owned)
            identity_error =
              std::max(identity_error,
                       std::abs(az[i] - (i == columns[k] ? 1. : 0.)));
        }
      EXPECT_LT(dealii::Utilities::MPI::max(identity_error, comm), 1e-13);

      if (kind == elasticity::Factorisation::klu ||
          kind == elasticity::Factorisation::mumps_unsymmetric)
        continue;
      // Symmetric with a negative diagonal entry: a Cholesky must refuse.
      if (owned.is_element(n / 2))
        A.set(n / 2, n / 2, -1.);
      A.compress(dealii::VectorOperation::insert);
      EXPECT_FALSE(solver->factorize(A));
      EXPECT_NE(solver->failure().find("not positive definite"),
                std::string::npos)
        << solver->failure();
    }
}



TEST(Elasticity, HistoryLoadAloneIsTheFullAssemblysRightHandSide)
{
  // What a transient step through contact::ContactSchur assembles: only
  // set 0's right-hand side, for a new history load on the kept operator.
  // It must equal that of a full assembly with the same load, with and
  // without an inhomogeneous set 0 and a stiffness load (the path that
  // needs the local K), leave set 1 alone, and refuse once the operator
  // changed (other factors, new constraint sets). Q2, on 1 and 2 ranks.
  const auto comm = MPI_COMM_WORLD;
  for (const bool inhomogeneous : {false, true})
    {
      const auto                      tria = box_mesh();
      elasticity::LinearElasticity<3> problem(*tria, 2, {{0, {E, nu, 7850.}}});
      problem.distribute_dofs();
      const auto fixed = [&](const double value) {
        return [&problem, value](dealii::AffineConstraints<double> &c) {
          dealii::VectorTools::interpolate_boundary_values(
            problem.dof_handler(),
            0,
            dealii::Functions::ConstantFunction<3>(value, 3),
            c);
        };
      };
      problem.setup_constraints({fixed(inhomogeneous ? 1e-3 : 0.), fixed(1.)});
      const auto &owned = problem.locally_owned_dofs();
      // Two different fields w (ghosted), smooth in the DoF number.
      const auto field = [&](const double k) {
        dealii::TrilinosWrappers::MPI::Vector o(owned, comm);
        for (const auto i : owned)
          o[i] = std::sin(k * i);
        o.compress(dealii::VectorOperation::insert);
        dealii::TrilinosWrappers::MPI::Vector g(owned,
                                                problem.locally_relevant_dofs(),
                                                comm);
        g = o;
        return g;
      };
      elasticity::DynamicTerms terms;
      terms.stiffness = 0.75;
      terms.mass      = 4e6;
      terms.mass_load = field(0.1);
      if (inhomogeneous)
        terms.stiffness_load = field(0.2);
      problem.set_dynamic_terms(terms);
      problem.assemble_sets({});
      const auto first = problem.right_hand_side(0);
      const auto unit  = problem.right_hand_side(1);

      terms.mass_load = field(0.3);
      if (inhomogeneous)
        terms.stiffness_load = field(0.4);
      problem.set_dynamic_terms(terms);
      ASSERT_TRUE(problem.assemble_history_load());
      dealii::TrilinosWrappers::MPI::Vector alone = problem.right_hand_side(0),
                                            one   = problem.right_hand_side(1);
      one -= unit;
      EXPECT_EQ(one.linfty_norm(), 0.) << "set 1 changed";
      problem.assemble_sets({});
      dealii::TrilinosWrappers::MPI::Vector full = problem.right_hand_side(0),
                                            change(full);
      change -= first;
      ASSERT_GT(change.l2_norm(), 0.1 * full.l2_norm());
      alone -= full;
      EXPECT_LT(alone.l2_norm(), 1e-13 * full.l2_norm())
        << (inhomogeneous ? "inhomogeneous" : "homogeneous");

      // Another factor of M, or constraint sets set up again: refused.
      terms.mass = 5e6;
      problem.set_dynamic_terms(terms);
      EXPECT_FALSE(problem.assemble_history_load());
      problem.assemble_sets({});
      EXPECT_TRUE(problem.assemble_history_load());
      problem.setup_constraints({fixed(0.), fixed(1.)});
      EXPECT_FALSE(problem.assemble_history_load());
    }
}



TEST(Heap, MatrixSizedBlocksGoBackToTheSystemWhenFreed)
{
  // This executable links deal.II, and with it the library whose static
  // initialiser turns mapped blocks off: without release_freed_memory() a
  // 64 MB block would stay in the heap after it is freed.
  process::release_freed_memory(32u << 20);
  ASSERT_EQ(process::mmap_threshold(), 32u << 20)
    << "CYCLOID_MMAP_THRESHOLD is set in the environment";
  const std::size_t mapped_before = mallinfo2().hblkhd;
  {
    std::vector<double> block((64u << 20) / sizeof(double), 1.);
    EXPECT_GE(mallinfo2().hblkhd, mapped_before + (64u << 20));
  }
  EXPECT_EQ(mallinfo2().hblkhd, mapped_before);
}



namespace
{
  /** This process's resident memory [bytes]. */
  std::size_t
  resident_bytes()
  {
    dealii::Utilities::System::MemoryStats stats;
    dealii::Utilities::System::get_memory_stats(stats);
    return stats.VmRSS * 1024;
  }
} // namespace



TEST(Heap, FreedSmallBlocksGoBackWhenThePagesAreGivenBack)
{
  // Small blocks (a dynamic sparsity pattern's rows) stay in the heap; the
  // libraries' setting never trims it. 300 MB of 1 kB blocks, freed, must
  // leave the process's resident memory only once the pages are given
  // back. A small block allocated after them keeps the heap's top from
  // being the free space, as in a run, where live data follows.
  process::release_freed_memory(32u << 20);
  ASSERT_EQ(process::mmap_threshold(), 32u << 20)
    << "CYCLOID_MMAP_THRESHOLD is set in the environment";
  constexpr std::size_t block = 1024, n = 300 * 1024;
  static_assert(n * block > process::give_back_threshold,
                "the call gives back only above its threshold");
  std::vector<std::unique_ptr<char[]>> blocks(n);
  for (auto &b : blocks)
    {
      b.reset(new char[block]);
      std::memset(b.get(), 1, block);
    }
  const std::unique_ptr<char[]> after(new char[block]);
  std::memset(after.get(), 1, block);
  const std::size_t with_blocks = resident_bytes();
  blocks.clear();
  blocks.shrink_to_fit();
  const std::size_t freed = resident_bytes();
  process::give_back_freed_pages();
  const std::size_t given_back = resident_bytes();
  // Freeing alone returns (almost) nothing: the pages are still mapped.
  EXPECT_GT(freed + (n * block) / 2, with_blocks);
  // Given back: at least three quarters of the 300 MB leave.
  EXPECT_LT(given_back + (3 * n * block) / 4, with_blocks)
    << "resident with the blocks " << with_blocks / 1048576 << " MB, freed "
    << freed / 1048576 << " MB, given back " << given_back / 1048576 << " MB";
}

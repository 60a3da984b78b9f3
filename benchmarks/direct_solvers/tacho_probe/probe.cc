// Tacho (Trilinos' Amesos2, Epetra adapter, 1 rank) against the project's
// factorisations (elasticity::DirectSolver) on one 3D elasticity matrix: a
// box of nx x nx x nz trilinear cells, clamped on its boundary, 84 sparse
// right-hand sides (issue #49 item 3; doc/solver-reuse.md, "Tacho").
//
//   cmake -S benchmarks/direct_solvers/tacho_probe -B /tmp/tacho-probe \
//         -DCYCLOID_BUILD=$PWD/build && make -C /tmp/tacho-probe
//   mpirun -np 1 /tmp/tacho-probe/probe [nx] [nz]
//
// Not part of the build: it documents a measurement. With Debian's Trilinos
// 13.2 the Tacho factorisation of this matrix stops with a segmentation
// fault (see doc/solver-reuse.md).
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/vector_tools.h>

#include <cycloid/elasticity/direct_solver.h>

#include <iostream>
#include <random>

#include <Amesos2.hpp>
#include <Epetra_CrsMatrix.h>
#include <Epetra_MultiVector.h>
#include <Kokkos_Core.hpp>
using namespace dealii;
int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (!Kokkos::is_initialized())
    Kokkos::initialize(argc, argv);
  {
    const unsigned nx      = argc > 1 ? std::atoi(argv[1]) : 60,
                   nz      = argc > 2 ? std::atoi(argv[2]) : 8;
    const unsigned   ncols = 84;
    Triangulation<3> tria;
    GridGenerator::subdivided_hyper_rectangle(tria,
                                              {nx, nx, nz},
                                              Point<3>(),
                                              Point<3>(nx, nx, nz));
    FESystem<3>   fe(FE_Q<3>(1), 3);
    DoFHandler<3> dh(tria);
    dh.distribute_dofs(fe);
    AffineConstraints<double> c;
    VectorTools::interpolate_boundary_values(dh,
                                             0,
                                             Functions::ZeroFunction<3>(3),
                                             c);
    c.close();
    DynamicSparsityPattern dsp(dh.n_dofs());
    DoFTools::make_sparsity_pattern(dh, dsp, c, false);
    TrilinosWrappers::SparseMatrix A;
    A.reinit(complete_index_set(dh.n_dofs()),
             complete_index_set(dh.n_dofs()),
             dsp,
             MPI_COMM_WORLD);
    QGauss<3>          q(2);
    FEValues<3>        fv(fe, q, update_gradients | update_JxW_values);
    const double       lambda = 1.2, mu = 0.8;
    FullMatrix<double> cm(24, 24);
    std::vector<types::global_dof_index> idx(24);
    for (auto &cell : dh.active_cell_iterators())
      {
        fv.reinit(cell);
        cm = 0;
        for (unsigned qp = 0; qp < q.size(); ++qp)
          for (unsigned i = 0; i < 24; ++i)
            for (unsigned j = 0; j < 24; ++j)
              {
                const unsigned ci = fe.system_to_component_index(i).first,
                               cj = fe.system_to_component_index(j).first;
                const auto gi = fv.shape_grad(i, qp), gj = fv.shape_grad(j, qp);
                cm(i, j) += (gi[ci] * gj[cj] * lambda + gi[cj] * gj[ci] * mu +
                             (ci == cj ? mu * (gi * gj) : 0.)) *
                            fv.JxW(qp);
              }
        cell->get_dof_indices(idx);
        c.distribute_local_to_global(cm, idx, A);
      }
    A.compress(VectorOperation::add);
    std::cout << "DoFs " << dh.n_dofs() << ", nonzeros "
              << A.n_nonzero_elements() << std::endl;
    std::vector<TrilinosWrappers::MPI::Vector> B(ncols), X(ncols);
    std::mt19937                               g(1);
    std::uniform_real_distribution<double>     d(-1, 1);
    for (unsigned k = 0; k < ncols; ++k)
      {
        B[k].reinit(complete_index_set(dh.n_dofs()), MPI_COMM_WORLD);
        X[k] = B[k];
        for (unsigned r = 0; r < 30; ++r)
          {
            auto i = g() % dh.n_dofs();
            if (!c.is_constrained(i))
              B[k][i] = d(g);
          }
        B[k].compress(VectorOperation::insert);
      }
    std::vector<TrilinosWrappers::MPI::Vector *>       xp;
    std::vector<const TrilinosWrappers::MPI::Vector *> bp;
    for (unsigned k = 0; k < ncols; ++k)
      {
        xp.push_back(&X[k]);
        bp.push_back(&B[k]);
      }
    TrilinosWrappers::MPI::Vector ref;
    for (auto f : {cycloid::elasticity::Factorisation::mumps,
                   cycloid::elasticity::Factorisation::cholmod_supernodal})
      {
        Timer t;
        auto  s = cycloid::elasticity::make_direct_solver(f, MPI_COMM_WORLD);
        s->factorize(A);
        const double tf = t.wall_time();
        s->solve(xp, bp);
        std::cout << cycloid::elasticity::to_string(f) << ": factorize " << tf
                  << " s, " << ncols << " solves " << t.wall_time() - tf
                  << " s, |x0| " << X[0].l2_norm() << std::endl;
        ref = X[0];
      }
    {
      Timer t;
      // Amesos2's Epetra adapter takes 32-bit maps; deal.II's are 64-bit.
      const Epetra_CrsMatrix &M = A.trilinos_matrix();
      Epetra_Map              map(int(dh.n_dofs()), 0, M.Comm());
      auto a = Teuchos::rcp(new Epetra_CrsMatrix(Copy, map, 81));
      for (int r = 0; r < M.NumMyRows(); ++r)
        {
          int     n;
          double *v;
          int    *ci;
          M.ExtractMyRowView(r, n, v, ci);
          std::vector<int> gc(n);
          for (int k = 0; k < n; ++k)
            gc[k] = int(M.ColMap().GID64(ci[k]));
          a->InsertGlobalValues(int(M.RowMap().GID64(r)), n, v, gc.data());
        }
      a->FillComplete();
      const double tcopy = t.wall_time();
      std::cout << "copy " << tcopy << " s" << std::endl;
      auto x = Teuchos::rcp(new Epetra_MultiVector(map, ncols));
      auto b = Teuchos::rcp(new Epetra_MultiVector(map, ncols));
      for (unsigned k = 0; k < ncols; ++k)
        for (int i = 0; i < b->MyLength(); ++i)
          (*b)[k][i] = B[k].trilinos_vector()[0][i];
      auto s =
        Amesos2::create<Epetra_CrsMatrix, Epetra_MultiVector>("tacho", a, x, b);
      {
        Teuchos::ParameterList  p("Amesos2");
        Teuchos::ParameterList &tp = p.sublist("Tacho");
        if (std::getenv("TACHO_VARIANT"))
          tp.set("variant", std::atoi(std::getenv("TACHO_VARIANT")));
        if (std::getenv("TACHO_SMALL"))
          tp.set("small problem threshold size",
                 std::atoi(std::getenv("TACHO_SMALL")));
        if (std::getenv("TACHO_METHOD"))
          tp.set("method", std::atoi(std::getenv("TACHO_METHOD")));
        s->setParameters(Teuchos::rcpFromRef(p));
      }
      t.restart();
      s->symbolicFactorization();
      const double ts = t.wall_time();
      s->numericFactorization();
      const double tf = t.wall_time();
      s->solve();
      const double tsol = t.wall_time() - tf;
      double       diff = 0;
      for (int i = 0; i < x->MyLength(); ++i)
        diff =
          std::max(diff, std::abs((*x)[0][i] - ref.trilinos_vector()[0][i]));
      std::cout << "tacho: symbolic " << ts << " s, numeric " << tf - ts
                << " s, " << ncols << " solves " << tsol
                << " s, max |x0 - mumps x0| " << diff << std::endl;
    }
  }
  Kokkos::finalize();
}

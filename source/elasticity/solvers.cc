// LinearElasticity, solvers: rigid-body modes and nodal blocks for the
// AMG, CG + ML AMG and the direct solvers, several right-hand sides, and
// residual norms.

#include <deal.II/base/exceptions.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>

#include <cycloid/elasticity/digest.h>
#include <cycloid/elasticity/elasticity.h>
#include <cycloid/elasticity/support_points.h>
#include <cycloid/process/heap.h>

#include <algorithm>
#include <iostream>

#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

namespace cycloid
{
  namespace elasticity
  {
    template <int dim>
    void
    LinearElasticity<dim>::owned_support_points(
      std::vector<dealii::Point<dim>> &point,
      std::vector<int>                &component) const
    {
      // From the owned cells only: deal.II's map_dofs_to_support_points()
      // maps every DoF of the shared mesh on every rank, into a std::map
      // of one node per DoF; on the 1.5 M-DoF seed case that took 2.8 s of
      // the first AMG set-up (doc/solver-reuse.md).
      point.assign(locally_owned.n_elements(), dealii::Point<dim>());
      component.assign(locally_owned.n_elements(), -1);
      auto values = support_point_values(*this);
      std::vector<dealii::types::global_dof_index> indices(
        fe.n_dofs_per_cell());
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            values.reinit(cell);
            cell->get_dof_indices(indices);
            for (unsigned int i = 0; i < indices.size(); ++i)
              if (locally_owned.is_element(indices[i]))
                {
                  const auto row = locally_owned.index_within_set(indices[i]);
                  const auto [c, node] = fe.system_to_component_index(i);
                  component[row]       = c;
                  point[row]           = values.quadrature_point(node);
                }
          }
    }



    template <int dim>
    bool
    LinearElasticity<dim>::nodal_blocks() const
    {
      if (blocked >= 0)
        return blocked == 1;
      // Row r of this rank must be component r % dim of the support point
      // of rows r - r % dim ... (deal.II numbers a vertex's components
      // together unless renumbered component-wise).
      std::vector<int>                component;
      std::vector<dealii::Point<dim>> point;
      owned_support_points(point, component);
      bool is_blocked = component.size() % dim == 0;
      for (std::size_t r = 0; is_blocked && r < component.size(); ++r)
        is_blocked = component[r] == static_cast<int>(r % dim) &&
                     point[r].distance(point[r - r % dim]) == 0.;
      this->blocked = dealii::Utilities::MPI::min(is_blocked ? 1 : 0, comm);
      return this->blocked == 1;
    }



    template <int dim>
    std::unique_ptr<Epetra_MultiVector>
    LinearElasticity<dim>::rigid_body_modes(const bool with_rotations) const
    {
      const unsigned int n_modes =
        dim + (with_rotations ? dim * (dim - 1) / 2 : 0);
      auto modes = std::make_unique<Epetra_MultiVector>(
        system_matrix.trilinos_matrix().RowMap(), n_modes);
      std::vector<int>                component;
      std::vector<dealii::Point<dim>> point;
      owned_support_points(point, component);
      for (std::size_t row = 0; row < point.size(); ++row)
        {
          const int c = component[row];
          if (c < 0)
            continue;
          const dealii::Point<dim> &x = point[row];
          (*modes)[c][row]            = 1.;
          if (!with_rotations)
            continue;
          // Rotation about z: (-y, x); in 3D also about x and y.
          if (c == 0)
            (*modes)[dim][row] = -x[1];
          if (c == 1)
            (*modes)[dim][row] = x[0];
          if (dim == 3)
            {
              if (c == 1)
                (*modes)[dim + 1][row] = -x[dim - 1];
              if (c == dim - 1)
                (*modes)[dim + 1][row] = x[1];
              if (c == dim - 1)
                (*modes)[dim + 2][row] = -x[0];
              if (c == 0)
                (*modes)[dim + 2][row] = x[dim - 1];
            }
        }
      return modes;
    }



    template <int dim>
    unsigned int
    LinearElasticity<dim>::solve(const Solver solver, const double tolerance)
    {
      return solve_set(0, solver, tolerance, locally_relevant_solution);
    }



    template <int dim>
    bool
    LinearElasticity<dim>::setup_preconditioner(const Solver solver)
    {
      if (is_direct(solver))
        {
          if (ready == Ready::direct)
            return false;
          ++n_builds;
          ready = Ready::direct;
          if (!try_factorisation())
            {
              direct = make_direct_solver(Factorisation::klu, comm);
              direct->factorize(system_matrix);
            }
          return true;
        }
      if (ready == Ready::amg || (ready == Ready::stale_amg && !rebuild_amg) ||
          dynamic.stiffness == 0.)
        return false;
      // ML with a user-given near-null space (deal.II 9.4 has no
      // extract_rigid_body_modes): translations and, unless asked
      // otherwise, rotations.
      dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.higher_order_elements = fe.degree > 1;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 0.02;
      Teuchos::ParameterList              parameters;
      std::unique_ptr<Epetra_MultiVector> unused;
      data.set_parameters(parameters, unused, system_matrix);
      // The modes depend on the DoFs only: built once per distribution
      // (they map the support points of the owned cells).
      const unsigned int n_modes =
        solver == Solver::cg_amg ? dim * (dim + 1) / 2 : dim;
      if (!null_space ||
          static_cast<unsigned int>(null_space->NumVectors()) != n_modes)
        null_space = rigid_body_modes(solver == Solver::cg_amg);
      // ML aggregates nodes, not single DoFs, when told that the rows come
      // in blocks of dim (one support point's components). Measured
      // (doc/solver-reuse.md): on a 3D two-disc scene of 290 k DoFs CG
      // needs about as many iterations, but the hierarchy is smaller, so
      // the solves take a fifth less, the set-up 40 % less and the run's
      // peak memory a fifth less; in 2D the solves took 15 % longer.
      if (dim == 3 && nodal_blocks())
        parameters.set("PDE equations", dim);
      parameters.set("null space: type", "pre-computed");
      parameters.set("null space: dimension", null_space->NumVectors());
      parameters.set("null space: vectors", null_space->Values());
      // Plain aggregation: the prolongator is the tentative one (no
      // damping step), and a W-cycle makes up its slower convergence.
      // Measured on the 3D seed case (doc/solver-reuse.md): peak memory
      // x0.70, set-ups x0.42, CG iterations 486 against 452, the whole
      // run x0.95.
      if (amg_hierarchy == AMGHierarchy::plain_w)
        {
          parameters.set("aggregation: damping factor", 0.);
          parameters.set("prec type", "MGW");
        }
      // A stale hierarchy goes before the new one is built (peak memory).
      amg.clear();
      amg.initialize(system_matrix, parameters);
      ready                = Ready::amg;
      rebuild_amg          = false;
      reference_iterations = 0;
      ++n_builds;
      return true;
    }



    template <int dim>
    bool
    LinearElasticity<dim>::try_factorisation()
    {
      // Every operator of this project with its supports is symmetric
      // positive definite; a matrix that is not (a body left free, a
      // formulation that breaks symmetry) goes to LU, and so does the rest
      // of the run rather than gathering and refusing again each time.
      if (factorisation_refused)
        return false;
      if (!direct || direct->kind() != factorisation)
        direct = make_direct_solver(factorisation, comm);
      if (direct->factorize(system_matrix))
        return true;
      dealii::ConditionalOStream(
        std::cerr, dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        << "  note: " << direct->failure()
        << "; the direct solver uses KLU (LU) from here on\n";
      factorisation_refused = true;
      direct.reset();
      return false;
    }



    template <int dim>
    unsigned int
    LinearElasticity<dim>::solve_set(const unsigned int k,
                                     const Solver       solver,
                                     const double       tolerance,
                                     dealii::TrilinosWrappers::MPI::Vector &u)
    {
      AssertThrow(k < rhs_sets.size(), dealii::ExcInternalError());
      const auto                           &rhs = rhs_sets[k];
      dealii::TrilinosWrappers::MPI::Vector x(locally_owned, comm);
      unsigned int                          iterations = 0;
      if (!is_direct(solver) && u.size() == x.size())
        {
          // Warm start from the caller's previous solution.
          for (const auto i : locally_owned)
            x[i] = u[i];
          x.compress(dealii::VectorOperation::insert);
        }
      const bool mass_only = dynamic.stiffness == 0.;
      if (!is_direct(solver) && mass_only)
        {
          // A mass operator (the projections of the time schemes): Jacobi
          // preconditions it as well as any hierarchy, at no set-up cost,
          // and leaves the stiffness operator's hierarchy to its own.
          if (!jacobi_ready)
            jacobi.initialize(system_matrix);
          jacobi_ready = true;
          dealii::SolverControl control(std::max<unsigned int>(1000,
                                                               rhs.size() / 10),
                                        tolerance * rhs.l2_norm());
          dealii::SolverCG<dealii::TrilinosWrappers::MPI::Vector> cg(control);
          cg.solve(system_matrix, x, rhs, jacobi);
          iterations = control.last_step();
        }
      else if (is_direct(solver))
        {
          setup_preconditioner(solver);
          direct->solve(x, rhs);
        }
      else
        {
          setup_preconditioner(solver);
          const unsigned int limit =
            std::max<unsigned int>(1000, rhs.size() / 10);
          // A kept hierarchy may take at most the iterations that would
          // trigger a rebuild; then CG goes on from there with a new one.
          const unsigned int rise  = (3 * reference_iterations + 10) / 2;
          const bool         stale = ready == Ready::stale_amg;
          try
            {
              iterations = run_cg(rhs, tolerance, stale ? rise : limit, x);
              if (reference_iterations == 0)
                reference_iterations = std::max(iterations, 1u);
            }
          catch (const dealii::SolverControl::NoConvergence &e)
            {
              AssertThrow(stale,
                          dealii::ExcMessage(
                            "elasticity: CG+AMG did not converge in " +
                            std::to_string(e.last_step) +
                            " iterations (residual " +
                            std::to_string(e.last_residual) +
                            "); is a body unconstrained?"));
              // CG leaves its last iterate in x: go on from it.
              rebuild_amg = true;
              setup_preconditioner(solver);
              iterations = e.last_step + run_cg(rhs, tolerance, limit, x);
              reference_iterations = std::max(iterations - e.last_step, 1u);
            }
        }
      constraint_sets[k].distribute(x);
      u.reinit(locally_owned, locally_relevant, comm);
      u = x;
      return iterations;
    }



    template <int dim>
    unsigned int
    LinearElasticity<dim>::run_cg(
      const dealii::TrilinosWrappers::MPI::Vector &rhs,
      const double                                 tolerance,
      const unsigned int                           max_steps,
      dealii::TrilinosWrappers::MPI::Vector       &x)
    {
      dealii::SolverControl control(max_steps, tolerance * rhs.l2_norm());
      dealii::SolverCG<dealii::TrilinosWrappers::MPI::Vector> cg(control);
      cg.solve(system_matrix, x, rhs, amg);
      return control.last_step();
    }



    template <int dim>
    dealii::FullMatrix<double>
    LinearElasticity<dim>::inverse_form(
      const std::vector<dealii::TrilinosWrappers::MPI::Vector> &r,
      const Factorisation                                       factorisation,
      std::string                                              *statistics)
    {
      if (!form_factor || form_factor->kind() != factorisation)
        {
          form_factor = make_direct_solver(factorisation, comm);
          AssertThrow(form_factor->factorize(system_matrix),
                      dealii::ExcMessage(
                        "elasticity: the " + to_string(factorisation) +
                        " factorisation failed: " + form_factor->failure() +
                        " (is a body unconstrained?)"));
        }
      auto form = form_factor->inverse_form(r);
      if (statistics)
        *statistics = form_factor->statistics();
      return form;
    }



    template <int dim>
    std::pair<double, double>
    LinearElasticity<dim>::residual_norms(
      const dealii::TrilinosWrappers::MPI::Vector &u,
      const unsigned int                           k) const
    {
      return residual_norms(u, constraint_sets.at(k), k == 0);
    }



    template <int dim>
    std::pair<double, double>
    LinearElasticity<dim>::residual_norms(
      const dealii::TrilinosWrappers::MPI::Vector &u,
      const dealii::AffineConstraints<double>     &constraints,
      const bool                                   with_load) const
    {
      dealii::TrilinosWrappers::MPI::Vector r(locally_owned, comm),
        f(locally_owned, comm);
      // Reference: the forces of the operator alone (A u) too; with a
      // history load, A u - b vanishes away from contacts and supports (a
      // free flight), so it cannot be the reference alone.
      const bool history = with_load && (dynamic.mass_load.size() > 0 ||
                                         dynamic.stiffness_load.size() > 0);
      dealii::TrilinosWrappers::MPI::Vector g(locally_owned, comm);
      assemble_internal_forces(u,
                               f,
                               &constraints,
                               &r,
                               true,
                               with_load,
                               nullptr,
                               history ? &g : nullptr);
      if (history)
        return {r.l2_norm(), std::max(f.l2_norm(), g.l2_norm())};
      return {r.l2_norm(), f.l2_norm()};
    }



    // The members this file defines, for both dimensions (one explicit
    // instantiation of the whole class, in elasticity.cc).
#define CYCLOID_INSTANTIATE(dim)                                              \
  template void LinearElasticity<dim>::owned_support_points(                  \
    std::vector<dealii::Point<dim>> &point, std::vector<int> &component)      \
    const;                                                                    \
  template bool LinearElasticity<dim>::nodal_blocks() const;                  \
  template std::unique_ptr<Epetra_MultiVector>                                \
  LinearElasticity<dim>::rigid_body_modes(const bool with_rotations) const;   \
  template unsigned int LinearElasticity<dim>::solve(const Solver solver,     \
                                                     const double tolerance); \
  template bool         LinearElasticity<dim>::setup_preconditioner(          \
    const Solver solver);                                             \
  template bool         LinearElasticity<dim>::try_factorisation();           \
  template unsigned int LinearElasticity<dim>::solve_set(                     \
    const unsigned int                     k,                                 \
    const Solver                           solver,                            \
    const double                           tolerance,                         \
    dealii::TrilinosWrappers::MPI::Vector &u);                                \
  template unsigned int LinearElasticity<dim>::run_cg(                        \
    const dealii::TrilinosWrappers::MPI::Vector &rhs,                         \
    const double                                 tolerance,                   \
    const unsigned int                           max_steps,                   \
    dealii::TrilinosWrappers::MPI::Vector       &x);                                \
  template dealii::FullMatrix<double> LinearElasticity<dim>::inverse_form(    \
    const std::vector<dealii::TrilinosWrappers::MPI::Vector> &r,              \
    const Factorisation                                       factorisation,  \
    std::string                                              *statistics);                                                 \
  template std::pair<double, double> LinearElasticity<dim>::residual_norms(   \
    const dealii::TrilinosWrappers::MPI::Vector &u, const unsigned int k)     \
    const;                                                                    \
  template std::pair<double, double> LinearElasticity<dim>::residual_norms(   \
    const dealii::TrilinosWrappers::MPI::Vector &u,                           \
    const dealii::AffineConstraints<double>     &constraints,                 \
    const bool                                   with_load) const;                                              \
  /* end */

    CYCLOID_INSTANTIATE(2)
    CYCLOID_INSTANTIATE(3)
#undef CYCLOID_INSTANTIATE
  } // namespace elasticity
} // namespace cycloid

// LinearElasticity, dynamic terms and energies: densities, the factors of
// the effective operator, internal and effective forces, energies and mass
// products.

#include <deal.II/base/exceptions.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>

#include <cycloid/elasticity/digest.h>
#include <cycloid/elasticity/elasticity.h>
#include <cycloid/elasticity/support_points.h>
#include <cycloid/process/heap.h>

#include <algorithm>
#include <iostream>

namespace cycloid
{
  namespace elasticity
  {
    template <int dim>
    double
    LinearElasticity<dim>::density(const dealii::types::material_id m) const
    {
      const auto it = materials.find(m);
      AssertThrow(it != materials.end(),
                  dealii::ExcMessage("elasticity: no material for body " +
                                     std::to_string(m)));
      // kg/m^3 -> t/mm^3 (N = t mm / s^2).
      return it->second.density * 1e-12;
    }



    template <int dim>
    void
    LinearElasticity<dim>::set_dynamic_terms(const DynamicTerms &terms)
    {
      AssertThrow(terms.stiffness >= 0 && terms.mass >= 0 &&
                    terms.stiffness + terms.mass > 0,
                  dealii::ExcMessage(
                    "elasticity: the effective operator needs non-negative "
                    "factors of K and M, not both zero."));
      // The matrix changes at the next assembly, which updates `ready`.
      dynamic = terms;
    }



    namespace
    {
      /**
       * The nodal forces of one cell at its quadrature points: @p op from
       * the operator's strains and (scaled) values, @p load from the history
       * load's; both reset first. Either value array may be empty (no
       * inertia, no mass load), the load's strains too.
       */
      template <int dim>
      void
      cell_forces(const dealii::FEValues<dim>                        &fe_values,
                  const double                                        lambda,
                  const double                                        mu,
                  const std::vector<dealii::SymmetricTensor<2, dim>> &strain,
                  const std::vector<dealii::Tensor<1, dim>>          &value,
                  const std::vector<dealii::SymmetricTensor<2, dim>> &strain_w,
                  const std::vector<dealii::Tensor<1, dim>>          &value_w,
                  dealii::Vector<double>                             &op,
                  dealii::Vector<double>                             &load)
      {
        const dealii::FEValuesExtractors::Vector disp(0);
        const auto stress = [&](const dealii::SymmetricTensor<2, dim> &e) {
          return lambda * dealii::trace(e) *
                   dealii::unit_symmetric_tensor<dim>() +
                 2 * mu * e;
        };
        op   = 0;
        load = 0;
        for (const unsigned int q : fe_values.quadrature_point_indices())
          {
            const auto   sigma   = stress(strain[q]);
            const auto   sigma_w = strain_w.empty() ?
                                     dealii::SymmetricTensor<2, dim>() :
                                     stress(strain_w[q]);
            const double JxW     = fe_values.JxW(q);
            for (unsigned int i = 0; i < op.size(); ++i)
              {
                const auto grad = fe_values[disp].symmetric_gradient(i, q);
                double     a    = sigma * grad;
                double     b    = strain_w.empty() ? 0. : sigma_w * grad;
                if (!value.empty() || !value_w.empty())
                  {
                    const auto v = fe_values[disp].value(i, q);
                    if (!value.empty())
                      a += value[q] * v;
                    if (!value_w.empty())
                      b += value_w[q] * v;
                  }
                op(i) += a * JxW;
                load(i) += b * JxW;
              }
          }
      }
    } // namespace



    template <int dim>
    void
    LinearElasticity<dim>::assemble_internal_forces(
      const dealii::TrilinosWrappers::MPI::Vector &u,
      dealii::TrilinosWrappers::MPI::Vector       &f,
      const dealii::AffineConstraints<double>     *condense,
      dealii::TrilinosWrappers::MPI::Vector       *condensed,
      const bool                                   effective,
      const bool                                   with_load,
      const CellList                              *cells,
      dealii::TrilinosWrappers::MPI::Vector       *operator_only) const
    {
      const dealii::QGauss<dim>                    quadrature(fe.degree + 1);
      dealii::FEValues<dim>                        fe_values(*map,
                                      fe,
                                      quadrature,
                                      dealii::update_values |
                                        dealii::update_gradients |
                                        dealii::update_JxW_values);
      const unsigned int                           n = fe.n_dofs_per_cell();
      dealii::Vector<double>                       cell_f(n), cell_load(n);
      std::vector<dealii::types::global_dof_index> indices(n);
      const dealii::FEValuesExtractors::Vector     disp(0);
      const std::size_t                            nq = quadrature.size();
      // f = s_K K u + s_M M u - (M w_M + K w_K), or K u; the arrays of
      // the terms that are not there stay empty.
      const double s_K = effective ? dynamic.stiffness : 1.;
      const double s_M = effective ? dynamic.mass : 0.;
      const bool   load_M =
        effective && with_load && dynamic.mass_load.size() > 0;
      const bool load_K =
        effective && with_load && dynamic.stiffness_load.size() > 0;
      std::vector<dealii::SymmetricTensor<2, dim>> strain(nq),
        strain_w(load_K ? nq : 0);
      std::vector<dealii::Tensor<1, dim>> value(s_M != 0. ? nq : 0),
        value_w(load_M ? nq : 0);
      CellList owned;
      if (!cells)
        for (const auto &cell : dofs.active_cell_iterators())
          if (cell->is_locally_owned())
            owned.push_back(cell);
      for (const auto &cell : cells ? *cells : owned)
        {
          const auto &m           = materials.at(cell->material_id());
          const auto [lambda, mu] = lame_parameters(m);
          const double rho        = density(cell->material_id());
          fe_values.reinit(cell);
          fe_values[disp].get_function_symmetric_gradients(u, strain);
          for (auto &e : strain)
            e *= s_K;
          if (load_K)
            fe_values[disp].get_function_symmetric_gradients(
              dynamic.stiffness_load, strain_w);
          if (!value.empty())
            {
              fe_values[disp].get_function_values(u, value);
              for (auto &v : value)
                v *= rho * s_M;
            }
          if (load_M)
            {
              fe_values[disp].get_function_values(dynamic.mass_load, value_w);
              for (auto &v : value_w)
                v *= rho;
            }
          cell_forces(fe_values,
                      lambda,
                      mu,
                      strain,
                      value,
                      strain_w,
                      value_w,
                      cell_f,
                      cell_load);
          cell->get_dof_indices(indices);
          if (operator_only)
            operator_only->add(indices, cell_f);
          cell_f -= cell_load;
          f.add(indices, cell_f);
          if (condense)
            condense->distribute_local_to_global(cell_f, indices, *condensed);
        }
      f.compress(dealii::VectorOperation::add);
      if (condensed)
        condensed->compress(dealii::VectorOperation::add);
      if (operator_only)
        operator_only->compress(dealii::VectorOperation::add);
    }



    template <int dim>
    dealii::TrilinosWrappers::MPI::Vector
    LinearElasticity<dim>::effective_forces(
      const dealii::TrilinosWrappers::MPI::Vector &u,
      const bool                                   with_load,
      const CellList                              *cells) const
    {
      dealii::TrilinosWrappers::MPI::Vector f(locally_owned, comm);
      assemble_internal_forces(u, f, nullptr, nullptr, true, with_load, cells);
      dealii::TrilinosWrappers::MPI::Vector ghosted(locally_owned,
                                                    locally_relevant,
                                                    comm);
      ghosted = f;
      return ghosted;
    }



    template <int dim>
    typename LinearElasticity<dim>::CellList
    LinearElasticity<dim>::owned_cells_touching(
      const std::vector<dealii::types::global_dof_index> &wanted) const
    {
      std::vector<dealii::types::global_dof_index> sorted(wanted);
      std::sort(sorted.begin(), sorted.end());
      CellList                                     cells;
      std::vector<dealii::types::global_dof_index> indices(
        fe.n_dofs_per_cell());
      for (const auto &cell : dofs.active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          cell->get_dof_indices(indices);
          for (const auto d : indices)
            if (std::binary_search(sorted.begin(), sorted.end(), d))
              {
                cells.push_back(cell);
                break;
              }
        }
      return cells;
    }



    template <int dim>
    std::pair<double, double>
    LinearElasticity<dim>::energies(
      const dealii::TrilinosWrappers::MPI::Vector &u,
      const dealii::TrilinosWrappers::MPI::Vector &v) const
    {
      const dealii::QGauss<dim>                    quadrature(fe.degree + 1);
      dealii::FEValues<dim>                        fe_values(*map,
                                      fe,
                                      quadrature,
                                      dealii::update_values |
                                        dealii::update_gradients |
                                        dealii::update_JxW_values);
      const dealii::FEValuesExtractors::Vector     disp(0);
      std::vector<dealii::SymmetricTensor<2, dim>> strain(quadrature.size());
      std::vector<dealii::Tensor<1, dim>>          velocity(quadrature.size());
      double                                       elastic = 0, kinetic = 0;
      for (const auto &cell : dofs.active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          const auto &m           = materials.at(cell->material_id());
          const auto [lambda, mu] = lame_parameters(m);
          const double rho        = density(cell->material_id());
          fe_values.reinit(cell);
          fe_values[disp].get_function_symmetric_gradients(u, strain);
          fe_values[disp].get_function_values(v, velocity);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const double tr = dealii::trace(strain[q]);
              elastic += 0.5 *
                         (lambda * tr * tr + 2 * mu * (strain[q] * strain[q])) *
                         fe_values.JxW(q);
              kinetic +=
                0.5 * rho * (velocity[q] * velocity[q]) * fe_values.JxW(q);
            }
        }
      return {dealii::Utilities::MPI::sum(elastic, comm),
              dealii::Utilities::MPI::sum(kinetic, comm)};
    }



    template <int dim>
    dealii::TrilinosWrappers::MPI::Vector
    LinearElasticity<dim>::mass_times(
      const dealii::TrilinosWrappers::MPI::Vector &x) const
    {
      const dealii::QGauss<dim>                    quadrature(fe.degree + 1);
      dealii::FEValues<dim>                        fe_values(*map,
                                      fe,
                                      quadrature,
                                      dealii::update_values |
                                        dealii::update_JxW_values);
      const unsigned int                           n = fe.n_dofs_per_cell();
      const dealii::FEValuesExtractors::Vector     disp(0);
      std::vector<dealii::Tensor<1, dim>>          value(quadrature.size());
      dealii::Vector<double>                       cell_f(n);
      std::vector<dealii::types::global_dof_index> indices(n);
      dealii::TrilinosWrappers::MPI::Vector        f(locally_owned, comm);
      for (const auto &cell : dofs.active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          const double rho = density(cell->material_id());
          fe_values.reinit(cell);
          fe_values[disp].get_function_values(x, value);
          cell_f = 0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            for (unsigned int i = 0; i < n; ++i)
              cell_f(i) += rho * (value[q] * fe_values[disp].value(i, q)) *
                           fe_values.JxW(q);
          cell->get_dof_indices(indices);
          f.add(indices, cell_f);
        }
      f.compress(dealii::VectorOperation::add);
      dealii::TrilinosWrappers::MPI::Vector ghosted(locally_owned,
                                                    locally_relevant,
                                                    comm);
      ghosted = f;
      return ghosted;
    }



    template <int dim>
    dealii::TrilinosWrappers::MPI::Vector
    LinearElasticity<dim>::internal_forces(
      const dealii::TrilinosWrappers::MPI::Vector &u) const
    {
      dealii::TrilinosWrappers::MPI::Vector f(locally_owned, comm);
      assemble_internal_forces(u, f, nullptr, nullptr);
      dealii::TrilinosWrappers::MPI::Vector ghosted(locally_owned,
                                                    locally_relevant,
                                                    comm);
      ghosted = f;
      return ghosted;
    }



    // The members this file defines, for both dimensions (one explicit
    // instantiation of the whole class, in elasticity.cc).
#define CYCLOID_INSTANTIATE(dim)                                           \
  template double LinearElasticity<dim>::density(                          \
    const dealii::types::material_id m) const;                             \
  template void LinearElasticity<dim>::set_dynamic_terms(                  \
    const DynamicTerms &terms);                                            \
  template void LinearElasticity<dim>::assemble_internal_forces(           \
    const dealii::TrilinosWrappers::MPI::Vector &u,                        \
    dealii::TrilinosWrappers::MPI::Vector       &f,                        \
    const dealii::AffineConstraints<double>     *condense,                 \
    dealii::TrilinosWrappers::MPI::Vector       *condensed,                \
    const bool                                   effective,                \
    const bool                                   with_load,                \
    const CellList                              *cells,                    \
    dealii::TrilinosWrappers::MPI::Vector       *operator_only) const;           \
  template dealii::TrilinosWrappers::MPI::Vector LinearElasticity<         \
    dim>::effective_forces(const dealii::TrilinosWrappers::MPI::Vector &u, \
                           const bool      with_load,                      \
                           const CellList *cells) const;                   \
  template typename LinearElasticity<dim>::CellList                        \
  LinearElasticity<dim>::owned_cells_touching(                             \
    const std::vector<dealii::types::global_dof_index> &wanted) const;     \
  template std::pair<double, double> LinearElasticity<dim>::energies(      \
    const dealii::TrilinosWrappers::MPI::Vector &u,                        \
    const dealii::TrilinosWrappers::MPI::Vector &v) const;                 \
  template dealii::TrilinosWrappers::MPI::Vector                           \
  LinearElasticity<dim>::mass_times(                                       \
    const dealii::TrilinosWrappers::MPI::Vector &x) const;                 \
  template dealii::TrilinosWrappers::MPI::Vector                           \
  LinearElasticity<dim>::internal_forces(                                  \
    const dealii::TrilinosWrappers::MPI::Vector &u) const;                 \
  /* end */

    CYCLOID_INSTANTIATE(2)
    CYCLOID_INSTANTIATE(3)
#undef CYCLOID_INSTANTIATE
  } // namespace elasticity
} // namespace cycloid

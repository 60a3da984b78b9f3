// LinearElasticity, assembly: the (effective) operator, the tractions of
// the load sets and the time schemes' history load.

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
    void
    LinearElasticity<dim>::assemble(
      const std::map<dealii::types::boundary_id, const dealii::Function<dim> *>
        &tractions)
    {
      assemble_sets(tractions);
    }



    namespace
    {
      /**
       * Everything the cell loop of LinearElasticity::assemble_sets() needs,
       * built once per assembly so that the loop allocates nothing.
       */
      template <int dim>
      struct AssemblyScratch
      {
        /** Size the local objects for @p fe and read the flags of
         * @p dynamic. */
        AssemblyScratch(const dealii::Mapping<dim>  &mapping,
                        const dealii::FESystem<dim> &fe,
                        const DynamicTerms          &dynamic)
          : fe_values(mapping,
                      fe,
                      dealii::QGauss<dim>(fe.degree + 1),
                      dealii::update_values | dealii::update_gradients |
                        dealii::update_JxW_values)
          , fe_face_values(mapping,
                           fe,
                           dealii::QGauss<dim - 1>(fe.degree + 1),
                           dealii::update_values |
                             dealii::update_quadrature_points |
                             dealii::update_JxW_values)
          , dofs_per_cell(fe.n_dofs_per_cell())
          , cell_matrix(dofs_per_cell, dofs_per_cell)
          , cell_rhs(dofs_per_cell)
          , indices(dofs_per_cell)
          , u(0)
          , eps(dofs_per_cell)
          , div(dofs_per_cell)
          , t(dim)
          , has_mass(dynamic.mass != 0.)
          // (Ghosted vectors: presence, not norm, decides.)
          , has_mass_load(dynamic.mass_load.size() > 0)
          , has_stiffness_load(dynamic.stiffness_load.size() > 0)
          , cell_mass(dofs_per_cell, dofs_per_cell)
          , cell_load(dofs_per_cell)
          , cell_w(dofs_per_cell)
          , comp_of(dofs_per_cell)
        {
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            comp_of[i] = fe.system_to_component_index(i).first;
        }

        /** Values, gradients and weights in the cell. */
        dealii::FEValues<dim> fe_values;
        /** Values and points on boundary faces (tractions). */
        dealii::FEFaceValues<dim> fe_face_values;
        /** DoFs per cell. */
        const unsigned int dofs_per_cell;
        /** Local effective operator s_K K + s_M M. */
        dealii::FullMatrix<double> cell_matrix;
        /** Local traction load (set 0: plus the history load). */
        dealii::Vector<double> cell_rhs;
        /** Copy of cell_rhs for the sets k > 0. */
        dealii::Vector<double> cell_rhs_k;
        /** Global DoFs of the cell. */
        std::vector<dealii::types::global_dof_index> indices;
        /** Displacement extractor. */
        const dealii::FEValuesExtractors::Vector u;
        /** Symmetric gradients of the shape functions at one point. */
        std::vector<dealii::SymmetricTensor<2, dim>> eps;
        /** Divergences of the shape functions at one point. */
        std::vector<double> div;
        /** Traction at one face point. */
        dealii::Vector<double> t;
        /** Whether the operator has a mass part s_M M. */
        const bool has_mass;
        /** Whether there is a history load M w_M. */
        const bool has_mass_load;
        /** Whether there is a history load K w_K. */
        const bool has_stiffness_load;
        /** Local mass matrix M. */
        dealii::FullMatrix<double> cell_mass;
        /** Local history load M w_M + K w_K. */
        dealii::Vector<double> cell_load;
        /** Local values of w_M or w_K. */
        dealii::Vector<double> cell_w;
        /** Component of each local DoF. */
        std::vector<unsigned int> comp_of;
      };



      /** Local stiffness K of @p cell (material from @p materials) into
       * @p s.cell_matrix, both triangles; reinitialises @p s.fe_values. */
      template <int dim>
      void
      assemble_local_stiffness(
        const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
        const std::map<dealii::types::material_id, parameters::ElasticMaterial>
                             &materials,
        AssemblyScratch<dim> &s)
      {
        const auto it = materials.find(cell->material_id());
        AssertThrow(it != materials.end(),
                    dealii::ExcMessage("elasticity: no material for body " +
                                       std::to_string(cell->material_id())));
        const auto [lambda, mu] = lame_parameters(it->second);

        const unsigned int dofs_per_cell = s.dofs_per_cell;
        s.cell_matrix                    = 0;
        s.fe_values.reinit(cell);
        for (const unsigned int q : s.fe_values.quadrature_point_indices())
          {
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              {
                s.eps[i] = s.fe_values[s.u].symmetric_gradient(i, q);
                s.div[i] = s.fe_values[s.u].divergence(i, q);
              }
            const double w = s.fe_values.JxW(q);
            // K is symmetric: sum the lower triangle, mirror it below.
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              for (unsigned int j = 0; j <= i; ++j)
                s.cell_matrix(i, j) += (2 * mu * (s.eps[i] * s.eps[j]) +
                                        lambda * s.div[i] * s.div[j]) *
                                       w;
          }
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          for (unsigned int j = i + 1; j < dofs_per_cell; ++j)
            s.cell_matrix(i, j) = s.cell_matrix(j, i);
      }



      /** History load M w_M + K w_K into @p s.cell_load, then
       * @p s.cell_matrix becomes s_K K + s_M M (@p dynamic). Needs
       * @p s.fe_values on the cell, @p s.indices and its density @p rho. */
      template <int dim>
      void
      add_dynamic_terms(const DynamicTerms   &dynamic,
                        const double          rho,
                        AssemblyScratch<dim> &s)
      {
        const unsigned int dofs_per_cell = s.dofs_per_cell;
        const auto        &fe_values     = s.fe_values;
        // K w_K needs the plain K, so it comes before the scaling by s_K.
        s.cell_load = 0;
        if (s.has_mass || s.has_mass_load)
          {
            s.cell_mass = 0;
            for (const unsigned int q : fe_values.quadrature_point_indices())
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                for (unsigned int j = 0; j < dofs_per_cell; ++j)
                  if (s.comp_of[i] == s.comp_of[j])
                    s.cell_mass(i, j) += rho * fe_values.shape_value(i, q) *
                                         fe_values.shape_value(j, q) *
                                         fe_values.JxW(q);
            if (s.has_mass_load)
              {
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  s.cell_w(i) = dynamic.mass_load[s.indices[i]];
                s.cell_mass.vmult_add(s.cell_load, s.cell_w);
              }
          }
        if (s.has_stiffness_load)
          {
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              s.cell_w(i) = dynamic.stiffness_load[s.indices[i]];
            s.cell_matrix.vmult_add(s.cell_load, s.cell_w);
          }
        if (dynamic.stiffness != 1.)
          s.cell_matrix *= dynamic.stiffness;
        if (s.has_mass)
          s.cell_matrix.add(dynamic.mass, s.cell_mass);
      }



      /** The local operator s_K K + s_M M of @p cell and its history load
       * into @p s, and its DoF indices. K is left out (zero) unless
       * @p with_k: a mass operator does not need it, nor does a history
       * load without K w_K when no inhomogeneity enters through the local
       * operator. @p density gives a body's density. */
      template <int dim, typename Density>
      void
      assemble_local_operator(
        const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
        const std::map<dealii::types::material_id, parameters::ElasticMaterial>
                             &materials,
        const bool            with_k,
        const Density        &density,
        const DynamicTerms   &dynamic,
        AssemblyScratch<dim> &s)
      {
        if (with_k)
          assemble_local_stiffness<dim>(cell, materials, s);
        else
          {
            s.cell_matrix = 0;
            s.fe_values.reinit(cell);
          }
        cell->get_dof_indices(s.indices);
        // The density is looked up only where the operator needs it.
        const double rho =
          s.has_mass || s.has_mass_load ? density(cell->material_id()) : 0.;
        add_dynamic_terms(dynamic, rho, s);
      }



      /** Boundary tractions of @p cell into @p s.cell_rhs (reset first). */
      template <int dim>
      void
      assemble_local_tractions(
        const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
        const std::map<dealii::types::boundary_id,
                       const dealii::Function<dim> *>                &tractions,
        const dealii::FESystem<dim>                                  &fe,
        AssemblyScratch<dim>                                         &s)
      {
        s.cell_rhs = 0;
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const auto tr = tractions.find(cell->face(f)->boundary_id());
              if (tr == tractions.end())
                continue;
              s.fe_face_values.reinit(cell, f);
              for (const unsigned int q :
                   s.fe_face_values.quadrature_point_indices())
                {
                  tr->second->vector_value(s.fe_face_values.quadrature_point(q),
                                           s.t);
                  for (unsigned int i = 0; i < s.dofs_per_cell; ++i)
                    {
                      const unsigned int c =
                        fe.system_to_component_index(i).first;
                      s.cell_rhs(i) += s.fe_face_values.shape_value(i, q) *
                                       s.t(c) * s.fe_face_values.JxW(q);
                    }
                }
            }
      }



      /** Add the local objects of @p s to @p matrix and to every right-hand
       * side in @p rhs, each through its constraint set in @p constraints. */
      template <int dim>
      void
      distribute_local(
        AssemblyScratch<dim>                                 &s,
        const std::vector<dealii::AffineConstraints<double>> &constraints,
        dealii::TrilinosWrappers::SparseMatrix               &matrix,
        std::vector<dealii::TrilinosWrappers::MPI::Vector>   &rhs)
      {
        // Sets k > 0 share the matrix; their inhomogeneities enter the
        // right-hand side through the local matrix. The history load
        // belongs to the first set only (superposition u = u_0 + beta u_1).
        for (unsigned int k = 1; k < constraints.size(); ++k)
          {
            s.cell_rhs_k = s.cell_rhs;
            constraints[k].distribute_local_to_global(s.cell_rhs_k,
                                                      s.indices,
                                                      rhs[k],
                                                      s.cell_matrix);
          }
        s.cell_rhs += s.cell_load;
        constraints[0].distribute_local_to_global(
          s.cell_matrix, s.cell_rhs, s.indices, matrix, rhs[0]);
      }
    } // namespace



    template <int dim>
    void
    LinearElasticity<dim>::assemble_sets(
      const std::map<dealii::types::boundary_id, const dealii::Function<dim> *>
        &tractions)
    {
      system_matrix = 0;
      for (auto &rhs : rhs_sets)
        rhs = 0;
      // Effective operator s_K K + s_M M and history load M w_M + K w_K.
      AssemblyScratch<dim> scratch(*map, fe, dynamic);
      // A mass operator (a projection) needs no K: it would be scaled by 0.
      const bool without_k =
        dynamic.stiffness == 0. && !scratch.has_stiffness_load;
      const auto density_of = [this](const dealii::types::material_id m) {
        return density(m);
      };
      for (const auto &cell : dofs.active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          assemble_local_operator<dim>(
            cell, materials, !without_k, density_of, dynamic, scratch);
          assemble_local_tractions<dim>(cell, tractions, fe, scratch);
          distribute_local(scratch, constraint_sets, system_matrix, rhs_sets);
        }
      system_matrix.compress(dealii::VectorOperation::add);
      for (auto &rhs : rhs_sets)
        rhs.compress(dealii::VectorOperation::add);
      assembled = AssembledOperator();
      if (tractions.empty())
        assembled = {constraint_setups, dynamic.stiffness, dynamic.mass};
      // A hierarchy on the same matrix object (fixed pattern) stays usable.
      jacobi_ready = false;
      ready        = ready == Ready::amg || ready == Ready::stale_amg ?
                       Ready::stale_amg :
                       Ready::none;
      form_factor.reset();
    }



    template <int dim>
    bool
    LinearElasticity<dim>::assemble_history_load()
    {
      if (assembled.constraint_setups != constraint_setups ||
          assembled.stiffness != dynamic.stiffness ||
          assembled.mass != dynamic.mass || rhs_sets.empty())
        return false;
      auto &rhs = rhs_sets[0];
      rhs       = 0;
      AssemblyScratch<dim> scratch(*map, fe, dynamic);
      const auto          &constraints = constraint_sets[0];
      // The local K only where the load or an inhomogeneity (entering the
      // right-hand side through the local operator) needs it: Newmark's
      // history load is M w_M alone.
      const bool need_k =
        scratch.has_stiffness_load || constraints.has_inhomogeneities();
      const auto density_of = [this](const dealii::types::material_id m) {
        return density(m);
      };
      for (const auto &cell : dofs.active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          assemble_local_operator<dim>(
            cell, materials, need_k, density_of, dynamic, scratch);
          constraints.distribute_local_to_global(scratch.cell_load,
                                                 scratch.indices,
                                                 rhs,
                                                 scratch.cell_matrix);
        }
      rhs.compress(dealii::VectorOperation::add);
      return true;
    }



    // The members this file defines, for both dimensions (one explicit
    // instantiation of the whole class, in elasticity.cc).
#define CYCLOID_INSTANTIATE(dim)                                              \
  template void LinearElasticity<dim>::assemble(                              \
    const std::map<dealii::types::boundary_id, const dealii::Function<dim> *> \
      &tractions);                                                            \
  template void LinearElasticity<dim>::assemble_sets(                         \
    const std::map<dealii::types::boundary_id, const dealii::Function<dim> *> \
      &tractions);                                                            \
  template bool LinearElasticity<dim>::assemble_history_load();               \
  /* end */

    CYCLOID_INSTANTIATE(2)
    CYCLOID_INSTANTIATE(3)
#undef CYCLOID_INSTANTIATE
  } // namespace elasticity
} // namespace cycloid

#include <deal.II/base/exceptions.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_solver.h>

#include <cycloid/elasticity/digest.h>
#include <cycloid/elasticity/elasticity.h>
#include <cycloid/elasticity/heap.h>
#include <cycloid/elasticity/support_points.h>

#include <algorithm>
#include <iostream>

#include <Amesos.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

namespace cycloid
{
  namespace elasticity
  {
    std::pair<double, double>
    lame_parameters(const parameters::ElasticMaterial &m)
    {
      const double E = m.youngs_modulus, nu = m.poissons_ratio;
      return {E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))};
    }



    template <int dim>
    LinearElasticity<dim>::LinearElasticity(
      const dealii::parallel::TriangulationBase<dim> &triangulation,
      const unsigned int                              degree,
      const std::map<dealii::types::material_id, parameters::ElasticMaterial>
        &materials)
      : triangulation(triangulation)
      , comm(triangulation.get_communicator())
      , fe(dealii::FE_Q<dim>(degree), dim)
      , map(std::make_unique<dealii::MappingQ<dim>>(degree))
      , dofs(triangulation)
      , materials(materials)
    {}



    template <int dim>
    void
    LinearElasticity<dim>::distribute_dofs()
    {
      dofs.distribute_dofs(fe);
      ++distributions;
      ++constraint_setups;
      locally_owned = dofs.locally_owned_dofs();
      blocked       = -1;
      update_relevant_dofs();
      hanging_all.clear();
      dealii::DoFTools::make_hanging_node_constraints(dofs, hanging_all);
      hanging_all.close();
      // The hierarchy refers to the modes: both go.
      release_matrix();
      pattern_fixed = false;
      null_space.reset();
    }



    template <int dim>
    void
    LinearElasticity<dim>::setup_constraints(
      const std::vector<
        std::function<void(dealii::AffineConstraints<double> &)>> &sets)
    {
      AssertThrow(!sets.empty(), dealii::ExcInternalError());
      ++constraint_setups;
      if (!pattern_fixed)
        update_relevant_dofs();
      constraint_sets.clear();
      constraint_sets.resize(sets.size());
      for (unsigned int k = 0; k < sets.size(); ++k)
        constraint_sets[k] = make_constraints(sets[k]);

      if (!pattern_fixed)
        {
          // The same lines and entries as the pattern was built for (e.g.
          // the supports alone, time step after time step): it stays.
          const std::size_t digest = structure_digest(constraint_sets[0]);
          const bool        same =
            dealii::Utilities::MPI::min(static_cast<int>(
                                          digest == pattern_digest &&
                                          system_matrix.m() == dofs.n_dofs()),
                                        comm) == 1;
          if (!same)
            build_exact_pattern();
          pattern_digest = digest;
        }
      rhs_sets.resize(sets.size());
      for (auto &rhs : rhs_sets)
        rhs.reinit(locally_owned, comm);
      locally_relevant_solution.reinit(locally_owned, locally_relevant, comm);
      many_solver.reset();
      many_problem.reset();
      // The old constraints' lines (and the dynamic pattern's rows, if the
      // pattern was rebuilt) are freed: their pages go back before the
      // assembly and the AMG set-up peak on top of them (where that is
      // worth it, see there).
      give_back_freed_pages();
    }



    template <int dim>
    std::size_t
    LinearElasticity<dim>::structure_digest(
      const dealii::AffineConstraints<double> &c)
    {
      // Each line's DoF and its entries' DoFs (not the weights).
      Digest digest;
      for (const auto &line : c.get_lines())
        {
          digest.add_word(line.index);
          digest.add_word(line.entries.size());
          for (const auto &entry : line.entries)
            digest.add_word(entry.first);
        }
      return digest.value();
    }



    template <int dim>
    dealii::AffineConstraints<double>
    LinearElasticity<dim>::make_constraints(
      const std::function<void(dealii::AffineConstraints<double> &)> &set) const
    {
      dealii::AffineConstraints<double> c;
      c.reinit(locally_relevant);
      dealii::DoFTools::make_hanging_node_constraints(dofs, c);
      set(c);
      c.close();
      return c;
    }



    template <int dim>
    void
    LinearElasticity<dim>::build_exact_pattern()
    {
      release_matrix();
      dealii::DynamicSparsityPattern dsp(locally_relevant);
      dealii::DoFTools::make_sparsity_pattern(dofs,
                                              dsp,
                                              constraint_sets[0],
                                              false);
      reinit_matrix(dsp);
    }



    template <int dim>
    void
    LinearElasticity<dim>::release_matrix()
    {
      // The matrix is about to be rebuilt on a new pattern: without this,
      // the old matrix and its AMG hierarchy would still be held while the
      // new pattern and matrix are allocated, and the peak of the run grows
      // by a third over its first active-set iteration (3D, 290 k DoFs,
      // doc/solver-reuse.md, "Memory").
      amg.clear();
      jacobi.clear();
      direct.reset();
      many_solver.reset();
      many_problem.reset();
      system_matrix.clear();
      ready        = Ready::none;
      jacobi_ready = false;
      assembled    = AssembledOperator();
    }



    template <int dim>
    void
    LinearElasticity<dim>::reinit_matrix(dealii::DynamicSparsityPattern &dsp)
    {
      dealii::SparsityTools::distribute_sparsity_pattern(dsp,
                                                         locally_owned,
                                                         comm,
                                                         locally_relevant);
      system_matrix.reinit(locally_owned, locally_owned, dsp, comm);
      ready = Ready::none;
    }



    template <int dim>
    void
    LinearElasticity<dim>::update_relevant_dofs()
    {
      // The extra relevant DoFs may have changed since distribute_dofs().
      dealii::DoFTools::extract_locally_relevant_dofs(dofs, locally_relevant);
      if (!extra_relevant.empty())
        {
          std::vector<dealii::types::global_dof_index> extra = extra_relevant;
          std::sort(extra.begin(), extra.end());
          extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
          locally_relevant.add_indices(extra.begin(), extra.end());
        }
    }



    template <int dim>
    void
    LinearElasticity<dim>::set_pattern_superset(
      const std::function<void(dealii::AffineConstraints<double> &)> &superset)
    {
      ++constraint_setups;
      release_matrix();
      update_relevant_dofs();
      // Unclosed, so that a chain of constraints stays visible: a set that
      // leaves a link of the chain unconstrained condenses onto that link.
      dealii::AffineConstraints<double> raw(locally_relevant);
      dealii::DoFTools::make_hanging_node_constraints(dofs, raw);
      superset(raw);
      dealii::DynamicSparsityPattern               dsp(locally_relevant);
      std::vector<dealii::types::global_dof_index> cell_dofs(
        fe.n_dofs_per_cell()),
        reach;
      for (const auto &cell : dofs.active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          cell->get_dof_indices(cell_dofs);
          // Every DoF the cell's DoFs can be condensed onto in any subset.
          reach = cell_dofs;
          for (std::size_t i = 0; i < reach.size(); ++i)
            if (raw.is_constrained(reach[i]))
              for (const auto &[m, w] : *raw.get_constraint_entries(reach[i]))
                if (std::find(reach.begin(), reach.end(), m) == reach.end())
                  reach.push_back(m);
          std::sort(reach.begin(), reach.end());
          for (const auto row : reach)
            dsp.add_entries(row, reach.begin(), reach.end(), true);
        }
      reinit_matrix(dsp);
      pattern_fixed = true;
    }



    template <int dim>
    void
    LinearElasticity<dim>::setup_system(
      const std::function<void(dealii::AffineConstraints<double> &)> &constrain)
    {
      distribute_dofs();
      setup_constraints({constrain});
    }



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
      many_solver.reset();
      many_problem.reset();
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
          ready        = Ready::direct;
          use_cholesky = solver == Solver::direct && try_cholesky();
          if (use_cholesky)
            return true;
          direct_control = std::make_unique<dealii::SolverControl>(1, 0);
          direct = std::make_unique<dealii::TrilinosWrappers::SolverDirect>(
            *direct_control,
            dealii::TrilinosWrappers::SolverDirect::AdditionalData(
              false,
              solver == Solver::direct_mumps ? "Amesos_Mumps" : "Amesos_Klu"));
          direct->initialize(system_matrix);
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
    LinearElasticity<dim>::try_cholesky()
    {
      // Every operator of this project with its supports is symmetric
      // positive definite; a matrix that is not (a body left free, a
      // formulation that breaks symmetry) goes to LU, and so does the rest
      // of the run rather than gathering and refusing again each time.
      if (cholesky_refused)
        return false;
      if (!cholesky)
        cholesky = std::make_unique<SparseCholesky>(comm);
      if (cholesky->factorize(system_matrix))
        return true;
      dealii::ConditionalOStream(
        std::cerr, dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        << "  note: " << cholesky->failure()
        << "; the direct solver uses KLU (LU) from here on\n";
      cholesky_refused = true;
      cholesky.reset();
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
          if (use_cholesky)
            cholesky->solve(x, rhs);
          else
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
    std::vector<dealii::TrilinosWrappers::MPI::Vector>
    LinearElasticity<dim>::solve_many(
      const std::vector<dealii::TrilinosWrappers::MPI::Vector> &rhs,
      const unsigned int                                        block)
    {
      const Epetra_CrsMatrix &A = system_matrix.trilinos_matrix();
      std::vector<dealii::TrilinosWrappers::MPI::Vector> solutions;
      if (!many_problem)
        {
          many_problem = std::make_shared<Epetra_LinearProblem>();
          many_problem->SetOperator(const_cast<Epetra_CrsMatrix *>(&A));
        }
      Epetra_LinearProblem &problem = *many_problem;
      for (unsigned int first = 0; first < rhs.size(); first += block)
        {
          const unsigned int n =
            std::min<unsigned int>(block, rhs.size() - first);
          Epetra_MultiVector B(A.RangeMap(), n), X(A.DomainMap(), n);
          for (unsigned int k = 0; k < n; ++k)
            {
              const Epetra_MultiVector &b = rhs[first + k].trilinos_vector();
              for (int i = 0; i < B.MyLength(); ++i)
                B[k][i] = b[0][i];
            }
          problem.SetLHS(&X);
          problem.SetRHS(&B);
          if (!many_solver)
            {
              Amesos factory;
              many_solver.reset(factory.Create("Amesos_Mumps", problem));
              AssertThrow(many_solver != nullptr,
                          dealii::ExcMessage(
                            "elasticity: Trilinos has no Amesos_Mumps."));
              AssertThrow(many_solver->SymbolicFactorization() == 0 &&
                            many_solver->NumericFactorization() == 0,
                          dealii::ExcMessage(
                            "elasticity: the MUMPS factorisation failed (is a "
                            "body unconstrained?)"));
            }
          AssertThrow(many_solver->Solve() == 0,
                      dealii::ExcMessage(
                        "elasticity: the MUMPS solve failed."));
          for (unsigned int k = 0; k < n; ++k)
            {
              dealii::TrilinosWrappers::MPI::Vector x(locally_owned, comm);
              Epetra_MultiVector                   &xv = x.trilinos_vector();
              for (int i = 0; i < X.MyLength(); ++i)
                xv[0][i] = X[k][i];
              constraint_sets[0].distribute(x);
              solutions.emplace_back(locally_owned, locally_relevant, comm);
              solutions.back() = x;
            }
        }
      return solutions;
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



    template class LinearElasticity<2>;
    template class LinearElasticity<3>;
  } // namespace elasticity
} // namespace cycloid

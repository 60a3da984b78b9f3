// LinearElasticity, system set-up: DoFs, constraint sets, sparsity
// patterns and the matrix (the other stages: assembly.cc, energies.cc,
// solvers.cc, after ASPECT's split of its Simulator by stage).

#include <deal.II/base/exceptions.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

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
      form_factor.reset();
      // The old constraints' lines (and the dynamic pattern's rows, if the
      // pattern was rebuilt) are freed: their pages go back before the
      // assembly and the AMG set-up peak on top of them (where that is
      // worth it, see there).
      process::give_back_freed_pages();
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
      // KLU holds the old matrix; CHOLMOD keeps its own copy and, for the
      // next matrix, its ordering.
      if (direct && direct->kind() == Factorisation::klu)
        direct.reset();
      form_factor.reset();
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



    template class LinearElasticity<2>;
    template class LinearElasticity<3>;
  } // namespace elasticity
} // namespace cycloid

#include <deal.II/base/mpi.h>

#include <cycloid/contact/active_set_solver.h>
#include <cycloid/contact/contact_problem.h>
#include <cycloid/contact/vtu_output.h>

#include <algorithm>
#include <limits>

namespace cycloid
{
  namespace contact
  {
    template <int dim>
    ContactProblem<dim>::ContactProblem(
      const dealii::parallel::TriangulationBase<dim> &triangulation,
      const unsigned int                              degree,
      const std::map<dealii::types::material_id, parameters::ElasticMaterial>
                            &materials,
      const ContactSettings &settings)
      : settings(settings)
      , materials(materials)
      , problem(
          std::make_unique<elasticity::LinearElasticity<dim>>(triangulation,
                                                              degree,
                                                              materials))
      , search(*problem)
      , formulation(
          create_formulation<dim>(formulation_name(settings.formulation)))
    {
      problem->set_amg_hierarchy(settings.amg_hierarchy);
      problem->set_factorisation(settings.factorisation);
    }



    template <int dim>
    void
    ContactProblem<dim>::set_contact(
      const std::set<dealii::types::material_id> &bodies,
      const dealii::types::boundary_id            surface,
      const std::vector<MasterCylinder>          &masters,
      const bool                                  deformable)
    {
      search.set_contact(bodies, surface, masters, deformable);
    }



    template <int dim>
    void
    ContactProblem<dim>::set_ties(const dealii::types::material_id body,
                                  const dealii::types::boundary_id surface)
    {
      search.set_ties(body, surface);
    }



    template <int dim>
    void
    ContactProblem<dim>::set_placement(
      const std::function<dealii::Point<dim>(dealii::types::material_id,
                                             const dealii::Point<dim> &)> &p)
    {
      search.set_placement(p);
    }



    template <int dim>
    void
    ContactProblem<dim>::set_timer(dealii::TimerOutput &t)
    {
      timer = &t;
    }



    template <int dim>
    void
    ContactProblem<dim>::setup()
    {
      problem->set_extra_relevant_dofs({});
      problem->distribute_dofs();
      search.collect_master_faces();
      find_slave_nodes();
      ties = search.find_tied_nodes();
      ghost_master_dofs();
      fix_pattern();
      solution.active.clear();
      fixed.clear();
      load.clear();
      reset_slave_results();
      force_dofs.clear();
      cells_at_forces.clear();
      solution.starts.clear();
    }



    template <int dim>
    const typename elasticity::LinearElasticity<dim>::CellList &
    ContactProblem<dim>::force_cells()
    {
      std::vector<dealii::types::global_dof_index> wanted;
      for (const auto &s : slaves)
        wanted.insert(wanted.end(), s.dofs.begin(), s.dofs.end());
      for (const auto &[d, g] : load)
        wanted.push_back(d);
      std::sort(wanted.begin(), wanted.end());
      wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
      // The same DoFs on the same mesh (setup() clears force_dofs): the
      // same cells. A time step's new candidates change them.
      if (wanted != force_dofs || wanted.empty())
        {
          cells_at_forces = problem->owned_cells_touching(wanted);
          force_dofs      = std::move(wanted);
        }
      return cells_at_forces;
    }



    template <int dim>
    void
    ContactProblem<dim>::find_slave_nodes()
    {
      slaves = search.find_slave_nodes(settings.search_distance);
      formulation->couple(search, slaves);
    }



    template <int dim>
    void
    ContactProblem<dim>::reset_slave_results()
    {
      solution.reactions.assign(slaves.size(), dealii::Tensor<1, dim>());
      solution.gaps.resize(slaves.size());
      for (unsigned int i = 0; i < slaves.size(); ++i)
        solution.gaps[i] = slaves[i].gap0;
    }



    namespace
    {
      /**
       * On a distributed mesh: the hanging lines of the master DoFs @p extra
       * (the same on every rank) into @p lines, and their parents appended
       * to @p extra (which comes back sorted, each DoF once, then the
       * parents). The owner of each master knows whether it hangs (its
       * cells are the owner's) and its closed line. Why: a master far from
       * a rank's cells may hang on cells the rank does not hold, and the
       * slave lines must condense onto its parents on every rank alike,
       * whose rows must be there. Collective.
       */
      template <int dim>
      void
      gather_master_hanging(const elasticity::LinearElasticity<dim> &problem,
                            const MPI_Comm                           comm,
                            std::vector<dealii::types::global_dof_index> &extra,
                            dealii::AffineConstraints<double>            &lines)
      {
        std::sort(extra.begin(), extra.end());
        extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
        const auto         &h     = problem.hanging_node_constraints();
        const auto         &owned = problem.locally_owned_dofs();
        std::vector<double> packed;
        for (const auto d : extra)
          if (owned.is_element(d) && h.is_constrained(d))
            {
              const auto &entries = *h.get_constraint_entries(d);
              packed.insert(packed.end(), {double(d), double(entries.size())});
              for (const auto &[m, w] : entries)
                packed.insert(packed.end(), {double(m), w});
            }
        packed = gather_all(comm, packed);
        for (const double *in = packed.data();
             in < packed.data() + packed.size();)
          {
            const auto d = static_cast<dealii::types::global_dof_index>(*in++);
            const auto n = static_cast<std::size_t>(*in++);
            lines.add_line(d);
            for (std::size_t k = 0; k < n; ++k, in += 2)
              {
                const auto m =
                  static_cast<dealii::types::global_dof_index>(in[0]);
                lines.add_entry(d, m, in[1]);
                extra.push_back(m);
              }
          }
      }
    } // namespace



    template <int dim>
    void
    ContactProblem<dim>::ghost_master_dofs()
    {
      // Every rank needs the master DoFs of all constraints it stores.
      std::vector<dealii::types::global_dof_index> extra;
      for (const auto &s : slaves)
        extra.insert(extra.end(), s.master_dofs.begin(), s.master_dofs.end());
      for (const auto &t : ties)
        for (unsigned int c = 0; c < dim; ++c)
          extra.insert(extra.end(), t.masters[c].begin(), t.masters[c].end());
      master_hanging.clear();
      if (search.distributed())
        gather_master_hanging(*problem,
                              search.communicator(),
                              extra,
                              master_hanging);
      problem->set_extra_relevant_dofs(extra);
    }



    template <int dim>
    std::vector<dealii::types::global_dof_index>
    ContactProblem<dim>::pattern_signature() const
    {
      std::vector<dealii::types::global_dof_index> sig;
      for (const auto &s : slaves)
        if (!s.hanging)
          {
            sig.push_back(s.dofs[0]);
            sig.insert(sig.end(), s.master_dofs.begin(), s.master_dofs.end());
          }
      return sig;
    }



    template <int dim>
    void
    ContactProblem<dim>::fix_pattern()
    {
      if (!settings.reuse_preconditioner)
        return;
      // Every active set is a subset of all candidates active, so one
      // pattern serves all states of these slaves and masters (and the AMG
      // hierarchy on it can be reused). Fixed and load DoFs are left out:
      // their lines have no masters, and a slave DoF among them only loses
      // entries in the real sets. (They may also still be the last mesh's.)
      problem->set_pattern_superset(
        [this](dealii::AffineConstraints<double> &c) {
          const std::vector<dealii::types::global_dof_index>      none;
          const std::map<dealii::types::global_dof_index, double> no_load;
          const ContactSystem<dim>                                system{
            slaves, ties, none, no_load, nullptr, &master_hanging};
          system.add_supports(c, 0.);
          for (const auto &s : slaves)
            if (!s.hanging)
              formulation->constrain(c, s, false);
        });
      signature = pattern_signature();
    }



    template <int dim>
    void
    ContactProblem<dim>::set_fixed_dofs(
      const std::vector<dealii::types::global_dof_index> &dofs)
    {
      fixed = dofs;
    }



    template <int dim>
    void
    ContactProblem<dim>::set_load(
      const std::map<dealii::types::global_dof_index, double> &g)
    {
      load = g;
    }



    template <int dim>
    void
    ContactProblem<dim>::update_geometry()
    {
      std::set<dealii::types::global_dof_index> was_active;
      for (const unsigned int i : solution.active)
        was_active.insert(slaves[i].dofs[0]);
      find_slave_nodes();
      // Collective: the slaves' masters may be known on some ranks only.
      const MPI_Comm comm =
        problem->dof_handler().get_triangulation().get_communicator();
      if (dealii::Utilities::MPI::max(static_cast<unsigned int>(
                                        pattern_signature() != signature),
                                      comm) > 0)
        {
          ghost_master_dofs();
          fix_pattern();
        }
      solution.active.clear();
      for (unsigned int i = 0; i < slaves.size(); ++i)
        if (!slaves[i].hanging && was_active.count(slaves[i].dofs[0]))
          solution.active.insert(i);
      reset_slave_results();
    }



    template <int dim>
    void
    ContactProblem<dim>::initialise_active_set(
      const std::function<bool(const SlaveNode<dim> &)> &predicate)
    {
      solution.active.clear();
      for (unsigned int i = 0; i < slaves.size(); ++i)
        if (!slaves[i].hanging && predicate(slaves[i]))
          solution.active.insert(i);
    }



    template <int dim>
    std::vector<std::pair<SlaveNode<dim>, bool>>
    ContactProblem<dim>::active_set_snapshot() const
    {
      std::vector<std::pair<SlaveNode<dim>, bool>> snapshot;
      for (unsigned int i = 0; i < slaves.size(); ++i)
        {
          SlaveNode<dim> s = slaves[i];
          s.master_dofs.clear();
          s.master_coefficients.clear();
          snapshot.emplace_back(s, solution.active.count(i) > 0);
        }
      return snapshot;
    }



    template <int dim>
    void
    ContactProblem<dim>::transfer_active_set(
      const std::vector<std::pair<SlaveNode<dim>, bool>> &snapshot)
    {
      std::map<std::pair<unsigned int, unsigned int>,
               std::vector<const std::pair<SlaveNode<dim>, bool> *>>
        groups;
      for (const auto &entry : snapshot)
        groups[{entry.first.body, entry.first.cylinder}].push_back(&entry);
      solution.active.clear();
      for (unsigned int i = 0; i < slaves.size(); ++i)
        {
          if (slaves[i].hanging)
            continue;
          const auto g = groups.find({slaves[i].body, slaves[i].cylinder});
          if (g == groups.end())
            continue;
          double best = std::numeric_limits<double>::max();
          bool   flag = false;
          for (const auto *entry : g->second)
            {
              const double d =
                entry->first.position.distance(slaves[i].position);
              if (d < best)
                {
                  best = d;
                  flag = entry->second;
                }
            }
          if (flag)
            solution.active.insert(i);
        }
    }



    template <int dim>
    void
    ContactProblem<dim>::assemble_without_contact()
    {
      const ContactSystem<dim> system{
        slaves, ties, fixed, load, nullptr, &master_hanging};
      problem->setup_constraints(
        {[&system](dealii::AffineConstraints<double> &c) {
          system.add_supports(c, 0.);
        }});
      problem->assemble_sets({});
    }



    template <int dim>
    ContactState
    ContactProblem<dim>::solve_load(const double       target,
                                    const std::string &label)
    {
      return solve_state(true, target, label);
    }



    template <int dim>
    ContactState
    ContactProblem<dim>::solve_displacement(const double       beta,
                                            const std::string &label)
    {
      return solve_state(false, beta, label);
    }



    template <int dim>
    ContactState
    ContactProblem<dim>::solve_state(const bool         load_control,
                                     const double       value,
                                     const std::string &label)
    {
      const ContactSystem<dim> system{
        slaves, ties, fixed, load, &force_cells(), &master_hanging};
      if (settings.schur_complement && !schur &&
          settings.solver == elasticity::LinearSolver::direct)
        schur = std::make_unique<ContactSchur<dim>>(
          problem->dof_handler().get_communicator(), settings.schur_columns);
      ActiveSetSolver<dim> solver(
        *problem, *formulation, settings, system, timer, schur.get());
      return solver.solve(load_control, value, label, solution);
    }



    template <int dim>
    void
    ContactProblem<dim>::write_vtu(const std::string &directory,
                                   const std::string &name) const
    {
      contact::write_vtu(
        *problem, materials, slaves, solution, directory, name);
    }



    template class ContactProblem<2>;
    template class ContactProblem<3>;
  } // namespace contact
} // namespace cycloid

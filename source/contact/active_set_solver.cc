#include <deal.II/base/exceptions.h>

#include <deal.II/base/utilities.h>

#include <cycloid/contact/active_set_solver.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>

#include <malloc.h>

namespace cycloid
{
  namespace contact
  {
    namespace
    {
      /** A TimerOutput::Scope if there is a timer, else nothing. */
      class OptionalScope
      {
      public:
        OptionalScope(dealii::TimerOutput *timer, const std::string &section)
        {
          if (timer)
            scope.emplace(*timer, section);
        }

      private:
        std::optional<dealii::TimerOutput::Scope> scope;
      };



      /** A CG tolerance as the debug output prints it, e.g. 1e-05. */
      std::string
      tolerance_label(const double tolerance)
      {
        std::ostringstream s;
        s.precision(0);
        s << std::scientific << tolerance;
        return s.str();
      }



      /** This process's resident memory now [MB] (debug output). */
      double
      resident_MB()
      {
        dealii::Utilities::System::MemoryStats stats;
        dealii::Utilities::System::get_memory_stats(stats);
        return stats.VmRSS / 1024.;
      }



      /** Heap in use by this process [MB] (debug output). */
      double
      in_use_MB()
      {
        const auto m = mallinfo2();
        return (m.uordblks + m.hblkhd) / 1048576.;
      }



      /** Where the heap is (debug output): the main arena's size and the
       * part of it that is free, and the blocks mapped on their own. */
      std::string
      heap_layout()
      {
        const auto m = mallinfo2();
        return "arena " + std::to_string(m.arena / 1048576) + " MB (free " +
               std::to_string(m.fordblks / 1048576) + "), mapped " +
               std::to_string(m.hblkhd / 1048576) + " MB";
      }



      /** This process's peak resident memory [MB] (debug output). */
      double
      peak_MB()
      {
        dealii::Utilities::System::MemoryStats stats;
        dealii::Utilities::System::get_memory_stats(stats);
        return stats.VmHWM / 1024.;
      }
    } // namespace



    template <int dim>
    ActiveSetSolver<dim>::ActiveSetSolver(
      elasticity::LinearElasticity<dim> &problem,
      const ConstraintFormulation<dim>  &formulation,
      const ContactSettings             &settings,
      const ContactSystem<dim>          &system,
      dealii::TimerOutput               *timer,
      ContactSchur<dim>                 *schur)
      : problem(problem)
      , formulation(formulation)
      , settings(settings)
      , system(system)
      , timer(timer)
      , schur(schur)
      , comm(problem.dof_handler().get_triangulation().get_communicator())
      , verbose(std::getenv("CYCLOID_DEBUG") &&
                dealii::Utilities::MPI::this_mpi_process(comm) == 0)
    {}



    template <int dim>
    ContactState
    ActiveSetSolver<dim>::solve(const bool            load_control,
                                const double          value,
                                const std::string    &label,
                                ContactSolution<dim> &solution)
    {
      ContactState                        state;
      std::vector<std::set<unsigned int>> history;
      // Loose solves while the set changes (they only decide the next
      // set), then the unchanged set once more to the tight tolerance. A
      // time step solves tight throughout: its right-hand side is
      // dominated by inertia, and CG's residual relative to it is no
      // measure of the contact forces.
      bool tight = settings.inner_tolerance <= settings.solver_tolerance ||
                   problem.dynamic_terms().mass != 0.;
      double       loose = settings.inner_tolerance;
      const double tightest =
        std::max(std::min(loose, loose_floor), settings.solver_tolerance);
      bool assembled = false;
      // Set after a cycle: the union of its sets is being solved.
      bool cycle_union = false;
      warm_start(solution);
      use_schur = schur != nullptr && begin_schur(state);
      for (unsigned int it = 0;; ++it)
        {
          AssertThrow(it < settings.max_iterations,
                      dealii::ExcMessage(
                        "contact: the active set did not settle in " +
                        std::to_string(settings.max_iterations) +
                        " iterations (Contact/Maximum active set iterations) "
                        "at " +
                        label + "."));
          // A cycle's union is solved 100 times tighter: the nodes that
          // came and went carry forces at the level of CG's residual.
          solve_iterate(solution.active,
                        assembled,
                        (tight ? settings.solver_tolerance : loose) *
                          (cycle_union ? cycle_tightening : 1.),
                        label + ", iteration " + std::to_string(it) +
                          (tight ? std::string(" (tight)") :
                                   " (loose " + tolerance_label(loose) + ")"),
                        state);

          if (!tight)
            loose = std::max(loose * loose_tightening, tightest);

          std::set<unsigned int> next;
          SetChange              change;
          std::size_t            moved = 0;
          {
            const OptionalScope scope(timer, "contact: active-set update");
            superpose(
              load_control, value, label, solution.active.empty(), state);
            next  = next_active_set(solution.active,
                                   state.beta,
                                   solution.gaps,
                                   change);
            moved = n_moved(solution.active, next);
          }
          if (verbose)
            std::cerr << "  [active set] " << label << ", iteration " << it
                      << ": beta " << state.beta << ", Q0 " << q0 << ", Q1 "
                      << q1 << ", active " << solution.active.size() << " -> "
                      << next.size() << " (" << moved
                      << " moved), largest tension " << change.largest_tension
                      << " of force " << change.largest_force << std::endl;
          assembled = next == solution.active;
          if (cycle_union)
            {
              // The union's solve decides: accepted, or an error.
              accept_cycle_union(change, label, state);
              break;
            }
          if (assembled && tight)
            break;
          if (assembled)
            {
              tight = true;
              history.clear();
            }
          else
            {
              // At most 1 % of the set (at least one node) moved.
              const bool small =
                !tight && moved <= std::max<std::size_t>(1, next.size() / 100);
              cycle_union =
                settle(solution.active, next, history, it, label, tight);
              if (small && !cycle_union)
                {
                  // A set that moved by a few nodes is most likely the
                  // last: solving it loose first would only repeat it.
                  tight = true;
                  history.clear();
                }
            }
        }
      finish(label, state, solution);
      keep_start(solution);
      return state;
    }



    template <int dim>
    void
    ActiveSetSolver<dim>::solve_iterate(const std::set<unsigned int> &active,
                                        const bool                    assembled,
                                        const double                  tolerance,
                                        const std::string            &iteration,
                                        ContactState                 &state)
    {
      clock.restart();
      const unsigned int builds = problem.n_preconditioner_builds();
      if (!assembled && !use_schur)
        assemble(active);
      if (!assembled)
        ++state.iterations;
      const double t_assemble = clock.wall_time();
      const double m_assemble = resident_MB();
      const double p_assemble = peak_MB();
      if (!use_schur)
        setup_preconditioner();
      const double t_preconditioner = clock.wall_time();
      const double m_preconditioner = resident_MB();
      const double p_preconditioner = peak_MB();
      if (use_schur)
        {
          // Exact solves: a set solved once needs no second look.
          const OptionalScope scope(timer, "contact: linear solves");
          if (!assembled)
            schur->solve_set(problem, contact_lines(active), u0, u1);
          n0 = n1 = 0;
        }
      else
        solve_linear_systems(tolerance, state);
      state.preconditioner_setups += problem.n_preconditioner_builds() - builds;
      if (!verbose)
        return;
      std::cerr << "  [active set] " << iteration << ": constraints+assembly "
                << t_assemble << " s, preconditioner "
                << t_preconditioner - t_assemble << " s, solves "
                << clock.wall_time() - t_preconditioner << " s / " << n0
                << " + " << n1 << " it, "
                << problem.n_preconditioner_builds() - builds << " builds"
                << (use_schur ?
                      ", Schur complement: " +
                        std::to_string(schur->n_columns()) + " columns kept, " +
                        std::to_string(schur->n_new_columns()) + " new, " +
                        std::to_string(schur->n_evictions_so_far()) +
                        " evictions" :
                      std::string())
                << "; rank 0 resident after assembly " << m_assemble
                << " MB, preconditioner " << m_preconditioner << " MB, solves "
                << resident_MB() << " MB, heap in use " << in_use_MB()
                << " MB, peak " << peak_MB() << " MB; " << heap_layout()
                << "; peak after assembly " << p_assemble
                << " MB, after preconditioner " << p_preconditioner << " MB"
                << std::endl;
    }



    template <int dim>
    void
    ActiveSetSolver<dim>::warm_start(const ContactSolution<dim> &solution)
    {
      const auto &terms = problem.dynamic_terms();
      for (const WarmStart &w : solution.starts)
        if (w.stiffness == terms.stiffness && w.mass == terms.mass &&
            w.u0.size() == problem.dof_handler().n_dofs())
          {
            u0 = w.u0;
            u1 = w.u1;
            return;
          }
    }



    template <int dim>
    void
    ActiveSetSolver<dim>::keep_start(ContactSolution<dim> &solution) const
    {
      const auto &terms  = problem.dynamic_terms();
      auto       &starts = solution.starts;
      starts.erase(std::remove_if(starts.begin(),
                                  starts.end(),
                                  [&terms](const WarmStart &w) {
                                    return w.stiffness == terms.stiffness &&
                                           w.mass == terms.mass;
                                  }),
                   starts.end());
      WarmStart w;
      w.stiffness = terms.stiffness;
      w.mass      = terms.mass;
      w.u0        = u0;
      w.u1        = u1;
      starts.insert(starts.begin(), std::move(w));
      if (starts.size() > 2)
        starts.resize(2);
    }



    template <int dim>
    void
    ContactSystem<dim>::add_supports(dealii::AffineConstraints<double> &c,
                                     const double beta) const
    {
      if (master_hanging)
        for (const auto &line : master_hanging->get_lines())
          if (c.can_store_line(line.index) && !c.is_constrained(line.index))
            {
              c.add_line(line.index);
              c.add_entries(line.index, line.entries);
            }
      for (const auto d : fixed)
        if (c.can_store_line(d) && !c.is_constrained(d))
          c.add_line(d);
      for (const auto &[d, g] : load)
        if (c.can_store_line(d) && !c.is_constrained(d))
          {
            c.add_line(d);
            c.set_inhomogeneity(d, beta * g);
          }
      for (const TiedNode<dim> &t : ties)
        for (unsigned int comp = 0; comp < dim; ++comp)
          {
            const auto d = t.dofs[comp];
            if (!c.can_store_line(d) || c.is_constrained(d))
              continue;
            c.add_line(d);
            for (unsigned int a = 0; a < t.masters[comp].size(); ++a)
              c.add_entry(d, t.masters[comp][a], t.weights[comp][a]);
          }
    }



    template <int dim>
    std::function<void(dealii::AffineConstraints<double> &)>
    ActiveSetSolver<dim>::constraint_set(const std::set<unsigned int> &active,
                                         const bool   with_gaps,
                                         const double beta) const
    {
      return
        [this, &active, with_gaps, beta](dealii::AffineConstraints<double> &c) {
          system.add_supports(c, beta);
          for (const unsigned int i : active)
            formulation.constrain(c, system.slaves[i], with_gaps);
        };
    }



    template <int dim>
    void
    ActiveSetSolver<dim>::assemble(const std::set<unsigned int> &active)
    {
      const OptionalScope scope(timer, "contact: constraints and assembly");
      // Set 0: the gaps, no load; set 1: the unit load, no gaps. Same
      // structure, so one matrix serves both (superposition).
      problem.setup_constraints(
        {constraint_set(active, true, 0.), constraint_set(active, false, 1.)});
      problem.assemble_sets({});
    }



    template <int dim>
    std::function<void(dealii::AffineConstraints<double> &)>
    ActiveSetSolver<dim>::contact_lines(
      const std::set<unsigned int> &active) const
    {
      return [this, &active](dealii::AffineConstraints<double> &c) {
        for (const unsigned int i : active)
          formulation.constrain(c, system.slaves[i], true);
      };
    }



    template <int dim>
    bool
    ActiveSetSolver<dim>::begin_schur(ContactState &state)
    {
      const std::set<unsigned int> none;
      const unsigned int           factorised = schur->n_factorisations();
      bool                         taken      = false;
      {
        const OptionalScope scope(timer, "contact: constraints and assembly");
        taken = schur->begin_state(problem,
                                   {constraint_set(none, true, 0.),
                                    constraint_set(none, false, 1.)});
      }
      state.preconditioner_setups += schur->n_factorisations() - factorised;
      if (!taken && verbose)
        std::cerr << "  [active set] the operator is not SPD: no Schur "
                     "complement, each set condensed"
                  << std::endl;
      return taken;
    }



    template <int dim>
    void
    ActiveSetSolver<dim>::setup_preconditioner()
    {
      const OptionalScope scope(timer, "contact: preconditioner");
      problem.setup_preconditioner(settings.solver);
    }



    template <int dim>
    void
    ActiveSetSolver<dim>::solve_linear_systems(const double  tolerance,
                                               ContactState &state)
    {
      const OptionalScope scope(timer, "contact: linear solves");
      n0 = problem.solve_set(0, settings.solver, tolerance, u0);
      n1 = problem.solve_set(1, settings.solver, tolerance, u1);
      state.linear_iterations += n0 + n1;
    }



    template <int dim>
    void
    ActiveSetSolver<dim>::superpose(const bool         load_control,
                                    const double       value,
                                    const std::string &label,
                                    const bool         free,
                                    ContactState      &state)
    {
      f0            = problem.effective_forces(u0, true, system.force_cells);
      f1            = problem.effective_forces(u1, false, system.force_cells);
      q0            = reaction(f0);
      q1            = reaction(f1);
      state.tangent = q1;
      if (load_control)
        {
          AssertThrow(std::abs(q1) > 0,
                      dealii::ExcMessage(
                        "contact: no contact node carries the load at " +
                        label +
                        " (the loaded body moves freely for this active set); "
                        "check the clearances and the search distance."));
          state.beta = (value - q0) / q1;
          // A free body (empty set; a quasi-static state, where nothing
          // else resists) turns to the wrong side or far beyond its first
          // contact: take the first closure instead. A beta short of it
          // (a transient step, the mass resisting) is the state.
          const double closure =
            free && value != 0 ? first_closure(value) : std::nan("");
          if (std::isfinite(closure) &&
              !(state.beta / closure >= 0 && state.beta / closure <= 1))
            state.beta = closure;
        }
      else
        state.beta = value;
      state.reaction = q0 + state.beta * q1;
    }



    template <int dim>
    double
    ActiveSetSolver<dim>::first_closure(const double value) const
    {
      // The gap is linear in beta: g(beta) = g(0) + beta (g(1) - g(0)).
      const auto  &owned = problem.locally_owned_dofs();
      const double sign  = value > 0 ? 1. : -1.;
      double       beta  = std::numeric_limits<double>::infinity();
      for (const SlaveNode<dim> &s : system.slaves)
        {
          if (s.hanging || !owned.is_element(s.dofs[0]))
            continue;
          const double g0    = formulation.gap(s, u0, u1, 0.);
          const double slope = sign * (formulation.gap(s, u0, u1, 1.) - g0);
          if (slope < 0 && g0 >= 0)
            beta = std::min(beta, -g0 / slope);
        }
      beta = dealii::Utilities::MPI::min(beta, comm);
      // Just past the closure, also where it is 0 (a node touching at the
      // start: it must enter, or the empty set would look converged).
      return std::isfinite(beta) ? sign * (beta * (1. + 1e-6) + 1e-12) :
                                   std::nan("");
    }



    template <int dim>
    std::set<unsigned int>
    ActiveSetSolver<dim>::next_active_set(const std::set<unsigned int> &active,
                                          const double                  beta,
                                          std::vector<double>          &gaps,
                                          SetChange &change) const
    {
      // lambda_i + c (-gap_i) > 0 with lambda = 0 off the set and gap = 0
      // on it: active nodes stay while in compression, inactive ones enter
      // when they penetrate. Each rank decides its owned nodes.
      const auto               &slaves = system.slaves;
      const auto               &owned  = problem.locally_owned_dofs();
      std::vector<unsigned int> mine;
      std::vector<double>       my_gaps(slaves.size(), 0.);
      for (unsigned int i = 0; i < slaves.size(); ++i)
        {
          const SlaveNode<dim> &s = slaves[i];
          if (s.hanging || !owned.is_element(s.dofs[0]))
            continue;
          double lambda = 0;
          for (unsigned int c = 0; c < 2; ++c)
            lambda += s.normal[c] * (f0[s.dofs[c]] + beta * f1[s.dofs[c]]);
          const double gap      = formulation.gap(s, u0, u1, beta);
          my_gaps[i]            = gap;
          const bool was_active = active.count(i);
          if ((was_active && lambda > 0) || (!was_active && gap < 0))
            mine.push_back(i);
          if (was_active)
            {
              change.largest_force = std::max(change.largest_force, lambda);
              if (lambda <= 0)
                change.largest_tension =
                  std::max(change.largest_tension, -lambda);
            }
          else if (gap < 0)
            change.entering = true;
        }
      std::set<unsigned int> next;
      for (const auto &part : dealii::Utilities::MPI::all_gather(comm, mine))
        next.insert(part.begin(), part.end());
      dealii::Utilities::MPI::sum(my_gaps, comm, gaps);
      change.largest_force =
        dealii::Utilities::MPI::max(change.largest_force, comm);
      change.largest_tension =
        dealii::Utilities::MPI::max(change.largest_tension, comm);
      change.entering =
        dealii::Utilities::MPI::max(static_cast<int>(change.entering), comm) >
        0;
      return next;
    }



    template <int dim>
    std::size_t
    ActiveSetSolver<dim>::n_moved(const std::set<unsigned int> &active,
                                  const std::set<unsigned int> &next)
    {
      std::vector<unsigned int> moved;
      std::set_symmetric_difference(active.begin(),
                                    active.end(),
                                    next.begin(),
                                    next.end(),
                                    std::back_inserter(moved));
      return moved.size();
    }



    template <int dim>
    bool
    ActiveSetSolver<dim>::settle(std::set<unsigned int>              &active,
                                 const std::set<unsigned int>        &next,
                                 std::vector<std::set<unsigned int>> &history,
                                 const unsigned int                   iteration,
                                 const std::string                   &label,
                                 bool &tight) const
    {
      const bool seen =
        std::find(history.begin(), history.end(), next) != history.end();
      if (seen && !tight)
        {
          // A loose solve may misjudge a node at the threshold: decide
          // again with tight solves before calling it cycling.
          tight = true;
          history.clear();
        }
      else if (seen)
        {
          // A tight cycle: the nodes that come and go sit where the
          // consistent mass or the masters' coupling (not an M-matrix)
          // makes a node penetrate when it is free and pull when it is
          // held. Hold every node of the cycle's sets; the caller checks
          // that the pull left is negligible (accept_cycle_union()).
          std::set<unsigned int> all(active.begin(), active.end());
          for (auto set = std::find(history.begin(), history.end(), next);
               set != history.end();
               ++set)
            all.insert(set->begin(), set->end());
          all.insert(next.begin(), next.end());
          if (verbose)
            std::cerr << "  [active set] " << label << ", iteration "
                      << iteration << ": cycle; solving the union of its "
                      << "sets, " << all.size() << " nodes" << std::endl;
          active = all;
          return true;
        }
      history.push_back(active);
      active = next;
      return false;
    }



    template <int dim>
    void
    ActiveSetSolver<dim>::accept_cycle_union(const SetChange   &change,
                                             const std::string &label,
                                             ContactState      &state) const
    {
      const double       tension = change.largest_force > 0 ?
                                     change.largest_tension / change.largest_force :
                                     std::numeric_limits<double>::infinity();
      std::ostringstream what;
      what << "contact: the active set cycles at " << label
           << ", and the union of the cycle's sets ";
      if (change.entering)
        what << "leaves a node penetrating";
      else
        what << "holds a node in tension at " << tension
             << " of the largest nodal force (at most " << cycle_tension_limit
             << " accepted)";
      what << ". Approach the load through a list of torques (each state "
              "starts from the set of the one before) or refine the contact "
              "mesh (Mesh/Contact refinements); doc/stability.md, "
              "\"Active-set cycling\".";
      AssertThrow(!change.entering && tension <= cycle_tension_limit,
                  dealii::ExcMessage(what.str()));
      ++state.cycles_broken;
      state.cycle_tension = std::max(state.cycle_tension, tension);
    }



    template <int dim>
    void
    ActiveSetSolver<dim>::finish(const std::string    &label,
                                 ContactState         &state,
                                 ContactSolution<dim> &solution) const
    {
      const OptionalScope scope(timer, "contact: residual and reactions");
      const auto         &owned = problem.locally_owned_dofs();
      {
        dealii::TrilinosWrappers::MPI::Vector a(owned, comm), b(owned, comm);
        a = u0;
        b = u1;
        a.add(state.beta, b);
        solution.displacement.reinit(owned,
                                     problem.locally_relevant_dofs(),
                                     comm);
        solution.displacement = a;
      }
      // Through the Schur complement, the problem's constraints are the
      // supports' alone; the residual is that of the whole set.
      const auto [r, f] =
        use_schur ?
          problem.residual_norms(solution.displacement,
                                 problem.make_constraints(
                                   constraint_set(solution.active, true, 0.)),
                                 true) :
          problem.residual_norms(solution.displacement, 0);
      state.residual = f > 0 ? r / f : 0.;
      AssertThrow(state.residual <= settings.residual_tolerance,
                  dealii::ExcMessage(
                    "contact: the converged active set leaves an equilibrium "
                    "residual of " +
                    std::to_string(state.residual) + " (relative) at " + label +
                    ", above " + std::to_string(settings.residual_tolerance) +
                    "; tighten Solver/Relative tolerance."));
      const auto         &slaves = system.slaves;
      std::vector<double> mine(slaves.size() * dim, 0.),
        all(slaves.size() * dim);
      for (const unsigned int i : solution.active)
        if (owned.is_element(slaves[i].dofs[0]))
          for (unsigned int c = 0; c < dim; ++c)
            mine[i * dim + c] =
              f0[slaves[i].dofs[c]] + state.beta * f1[slaves[i].dofs[c]];
      dealii::Utilities::MPI::sum(mine, comm, all);
      for (unsigned int i = 0; i < slaves.size(); ++i)
        for (unsigned int c = 0; c < dim; ++c)
          solution.reactions[i][c] = all[i * dim + c];
      state.n_active = solution.active.size();
    }



    template <int dim>
    double
    ActiveSetSolver<dim>::reaction(
      const dealii::TrilinosWrappers::MPI::Vector &f) const
    {
      double q = 0;
      for (const auto &[d, g] : system.load)
        if (problem.locally_owned_dofs().is_element(d))
          q += g * f[d];
      return dealii::Utilities::MPI::sum(q, comm);
    }



    template struct ContactSystem<2>;
    template struct ContactSystem<3>;
    template class ActiveSetSolver<2>;
    template class ActiveSetSolver<3>;
  } // namespace contact
} // namespace cycloid

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include <cycloid/postprocess/report.h>
#include <cycloid/postprocess/solution_record.h>
#include <cycloid/results/cost_figures.h>
#include <cycloid/runs/phase_sweep.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>

namespace cycloid
{
  namespace runs
  {
    namespace
    {
      namespace u = results::units;
      using results::Clock;
      using results::seconds_since;

      /** The settings of this rank's group: the scenes outside world rank
       * 0's group print nothing (their group roots would interleave their
       * lines with rank 0's). */
      FeRunSettings
      group_settings(const FeRunSettings &settings, const PhaseGroups &groups)
      {
        FeRunSettings s = settings;
        s.stage.quiet   = groups.group() != 0;
        return s;
      }

      /** Load @p t of @p loads on @p scene, warm-started from @p snapshot
       * (this load's state at the group's previous phase), which then
       * becomes this state's active set. */
      template <int dim>
      results::StageState
      solve_load(stage::StageScene<dim>              &scene,
                 stage::ActiveSetSnapshot<dim>       &snapshot,
                 const parameters::LoadingParameters &loading,
                 const std::vector<double>           &loads,
                 const unsigned int                   t)
      {
        if (cycle_zero(loading, loads, t))
          return scene.zero_torque_limit(
            parameters::LoadingParameters::zero_side(loads, t));
        scene.warm_start(snapshot);
        results::StageState state = scene.solve(loads[t]);
        snapshot                  = scene.active_set_snapshot();
        return state;
      }



      /**
       * @brief World rank 0's side of a sweep: prints each state as it
       * arrives from any group, and writes the states through the one
       * Report and SolutionRecord in phase order, holding back those that
       * arrive before their predecessors. Built on every rank; only rank 0
       * takes states.
       */
      class SweepOutput
      {
      public:
        SweepOutput(const FeRunSettings                    &settings,
                    const std::vector<double>              &angles,
                    const PhaseGroups                      &groups,
                    const MPI_Comm                          comm,
                    const Clock::time_point                 start,
                    const std::vector<std::vector<double>> &coarser)
          : settings(settings)
          , angles(angles)
          , groups(groups)
          , loads(settings.loading.load_values())
          , n_states(angles.size() * loads.size())
          , start(start)
          , report(options(settings, coarser), comm)
          , record(settings.stage.output_directory, comm)
        {}

        /** Print @p states, then write every state that is next in phase
         * order. */
        void
        take(const std::vector<results::StageState> &states)
        {
          for (const results::StageState &s : states)
            {
              ++arrived;
              print(s);
              early.emplace(s.step, s);
            }
          for (auto s = early.find(next); s != early.end();
               s      = early.find(next))
            {
                   const unsigned int t = next % loads.size();
                   report.write(s->second, loads[t]);
                   // (A zero-torque limit has no field of its own.)
                   if (settings.write_solution &&
                  !cycle_zero(settings.loading, loads, t))
                record.add(next,
                           postprocess::SolutionRecord::name(next) + ".pvtu");
              early.erase(s);
                   ++next;
            }
        }

        /** The written sweep's largest noise floor over fluctuation
         * (Report::noise_ratio; world rank 0). */
        double
        noise_ratio() const
        {
          return report.noise_ratio();
        }

        /** K_tangent over the phases per load (world rank 0). */
        std::vector<std::vector<double>>
        k_tangent_series() const
        {
          return report.k_tangent_series();
        }

        /** Whether every state has been written. */
        bool
        complete() const
        {
          return next == n_states;
        }

        /** Print each group's busy time @p busy [s] (several groups), then
         * finish the report. */
        void
        finish(const std::vector<double> &busy) const
        {
          if (groups.n_groups() > 1)
            {
              std::cout << "  phase groups of " << groups.group_size()
                        << " rank(s), busy time:" << std::setprecision(3);
              for (unsigned int g = 0; g < groups.n_groups(); ++g)
                std::cout << (g > 0 ? ";" : "") << " group " << g << " (phases "
                          << groups.first_phase(g) + 1 << "-"
                          << groups.first_phase(g + 1) << ") " << busy[g]
                          << " s";
              std::cout << "; the sweep " << seconds_since(start) << " s"
                        << std::setprecision(6) << std::endl;
            }
          report.finish();
        }

      private:
        /** The report's options: @p coarser is the previous pass's
         * K_tangent per load (empty: none). */
        static postprocess::Report::Options
        options(const FeRunSettings                    &settings,
                const std::vector<std::vector<double>> &coarser)
        {
          auto o              = report_options(settings);
          o.coarser_k_tangent = coarser;
          // A repeat pass runs with the target off, but the sweep's
          // target still decides after it.
          o.sweep_target =
            !coarser.empty() || settings.stage.mesh.error.target_accuracy > 0;
          return o;
        }

        /** The progress line of @p s: its phase, the time so far and the
         * time the states not yet arrived will take at this rate. */
        void
        print(const results::StageState &s) const
        {
          const unsigned int k       = s.step / loads.size();
          const double       elapsed = seconds_since(start);
          std::ostringstream prefix;
          prefix << "  phase " << k + 1 << "/" << angles.size() << " (crank "
                 << std::setprecision(5) << angles[k] * u::deg_per_rad
                 << " deg";
          if (groups.n_groups() > 1)
            prefix << ", group " << groups.group_of(k);
          prefix << "), elapsed " << std::setprecision(3) << elapsed
                 << " s, remaining ~"
                 << elapsed * (n_states - arrived) / arrived
                 << " s: " << std::setprecision(6);
          report.print(s, prefix.str());
        }

        const FeRunSettings                        &settings;
        const std::vector<double>                  &angles;
        const PhaseGroups                          &groups;
        const std::vector<double>                   loads;
        const unsigned int                          n_states;
        const Clock::time_point                     start;
        postprocess::Report                         report;
        postprocess::SolutionRecord                 record;
        std::map<unsigned int, results::StageState> early;
        unsigned int                                next    = 0;
        unsigned int                                arrived = 0;
      };
    } // namespace



    template <int dim>
    PhaseSweepRun<dim>::PhaseSweepRun(const FeRunSettings &settings,
                                      const MPI_Comm       comm)
      : comm(comm)
      , angles(settings.loading.crank_angles(
          geometry::CycloidGeometry(settings.stage.geometry).mesh_period()))
      , groups(comm, settings.loading.ranks_per_phase_group, angles.size())
      , settings(group_settings(settings, groups))
    {
      dealii::ConditionalOStream out(
        std::cout, dealii::Utilities::MPI::this_mpi_process(comm) == 0);
      out << "cycloid-contact: phase sweep, FE contact, "
          << stage::description(settings.stage) << ", " << angles.size()
          << " crank angles over "
          << geometry::CycloidGeometry(settings.stage.geometry).mesh_period() *
               u::deg_per_rad
          << " deg x " << settings.loading.load_values().size() << " load(s)";
      if (groups.n_groups() > 1)
        out << ", " << groups.n_groups() << " phase groups of "
            << groups.group_size() << " rank(s)";
      out << std::endl;
      first = make_scene(groups.first_phase(groups.group()), this->settings);
    }



    template <int dim>
    std::unique_ptr<stage::StageScene<dim>>
    PhaseSweepRun<dim>::make_scene(const unsigned int   k,
                                   const FeRunSettings &s) const
    {
      mesh::MeshRequest request = mesh_request(s, angles[k]);
      // A one-group sweep rewrote stage.msh at every phase, leaving the last
      // phase's; groups would write it at the same time, so only the last
      // phase's scene writes it.
      if (k + 1 != angles.size())
        request.msh_file.clear();
      return std::make_unique<stage::StageScene<dim>>(s.stage,
                                                      request,
                                                      groups.comm());
    }



    template <int dim>
    double
    PhaseSweepRun<dim>::sweep(
      const FeRunSettings                    &s,
      std::unique_ptr<stage::StageScene<dim>> first_scene,
      std::vector<std::vector<double>>       &k_tangent,
      unsigned int                           &finest) const
    {
      const auto     start = Clock::now();
      SweepOutput    output(s, angles, groups, comm, start, k_tangent);
      StateCollector collector(groups, comm);
      // This group's solution files; world rank 0's record lists them all.
      postprocess::SolutionRecord pieces(s.stage.output_directory,
                                         groups.comm(),
                                         false);
      const bool writer = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      const std::vector<double> loads = s.loading.load_values();
      // Per load: the group's last phase's active set (the warm start of
      // its next phase).
      std::vector<stage::ActiveSetSnapshot<dim>> snapshots(loads.size());
      const unsigned int begin = groups.first_phase(groups.group()),
                         end   = groups.first_phase(groups.group() + 1);
      for (unsigned int k = begin; k < end; ++k)
        {
          auto scene = k == begin ? std::move(first_scene) : make_scene(k, s);
          // The group's first phase stands for the sweep's resolution.
          if (k == begin)
            scene->announce_resolution(largest_load(loads));
          for (unsigned int t = 0; t < loads.size(); ++t)
            {
              results::StageState state =
                solve_load(*scene, snapshots[t], s.loading, loads, t);
              state.step = k * loads.size() + t;
              // The files first: the record lists only files that exist.
              if (s.write_solution && !cycle_zero(s.loading, loads, t))
                {
                  const std::string name =
                    postprocess::SolutionRecord::name(state.step);
                  scene->output_results(name);
                  pieces.add(state.step, name + ".pvtu");
                }
              finest = std::max(finest, scene->contact_level());
              collector.submit(state);
              if (writer)
                output.take(collector.receive(false));
            }
        }
      const double busy = seconds_since(start);
      collector.finish(busy);
      double ratio = 0;
      if (writer)
        {
          while (!output.complete())
            output.take(collector.receive(true));
          output.finish(collector.busy_times(busy));
          ratio     = output.noise_ratio();
          k_tangent = output.k_tangent_series();
        }
      // Collectives only after world rank 0 has taken every state: the
      // group roots' sends may wait for it.
      finest = dealii::Utilities::MPI::max(finest, comm);
      return dealii::Utilities::MPI::broadcast(comm, ratio, 0);
    }



    template <int dim>
    bool
    PhaseSweepRun<dim>::sweep_again(const unsigned int pass,
                                    const unsigned int level,
                                    const unsigned int next,
                                    const double       ratio,
                                    const double       previous) const
    {
      const auto                &e = settings.stage.mesh.error;
      dealii::ConditionalOStream out(
        std::cout, dealii::Utilities::MPI::this_mpi_process(comm) == 0);
      const std::string at = " at Contact refinements " +
                             std::to_string(level) + " (pass " +
                             std::to_string(pass + 1) + ")";
      // One phase has no fluctuation to resolve.
      if (e.target_accuracy == 0 || angles.size() < 2)
        return false;
      if (ratio < 0.5)
        {
          out << "  target accuracy: the sweep's fluctuation is resolved" << at
              << ", its largest noise floor " << ratio << " of the fluctuation"
              << std::endl;
          return false;
        }
      if (std::isnan(ratio))
        {
          out << "  target accuracy: the sweep cannot say whether its "
                 "fluctuation is resolved: its noise floor is unknown (use "
                 "Loading/Number of phases >= 9)"
              << std::endl;
          return false;
        }
      if (e.automatic_target)
        {
          // A repeat refines every phase to one level beyond the finest:
          // measured on the 9-phase example, contact level 6 and 1.6 M
          // DoFs in every phase, half an hour a state. Not for a default.
          out << "  target accuracy = auto: the fluctuation is not resolved"
              << at << " (noise floor " << ratio
              << " of it, resolved below 0.5); an automatic target does not "
                 "repeat the sweep finer (each repeat refines every phase "
                 "and costs minutes to hours in 2D): set Mesh/Target "
                 "accuracy to a number (e.g. 0.01) to repeat it up to "
                 "Mesh/Maximum sweep refinements times"
              << std::endl;
          return false;
        }
      const unsigned int left = e.max_sweep_refinements - pass;
      // The floor must fall to half the fluctuation; the fall of the
      // last pass says how many more it would take.
      const double       fall   = previous / ratio;
      const double       needed = std::log(2 * ratio) / std::log(fall);
      std::ostringstream why;
      why << std::setprecision(3) << "  target accuracy: the fluctuation is "
          << "not resolved" << at << ": the noise floor is " << ratio
          << " of it (resolved below 0.5)";
      if (left == 0)
        why << "; Mesh/Maximum sweep refinements (" << e.max_sweep_refinements
            << ") allows no further pass";
      else if (!std::isnan(previous) && !(fall > 1.05))
        why << "; the last refinement did not lower it (from " << previous
            << "): the sweep CANNOT resolve this fluctuation by refining; "
               "the stage's own fluctuation is likely below the mesh "
               "noise";
      else if (!std::isnan(previous) && needed > left)
        why << "; at the last pass's rate (floor / fluctuation fell " << fall
            << " times) it would take about " << std::ceil(needed)
            << " more passes, " << left
            << " allowed (Mesh/Maximum sweep refinements): the sweep "
               "CANNOT resolve it within its limits";
      else
        {
          out << why.str() << "; sweeping again at Contact refinements " << next
              << " in every phase (one beyond this pass's finest), to "
                 "measure the noise as the change between the passes"
              << std::endl;
          return true;
        }
      if (left == 0)
        why << ": the fluctuation is NOT resolved";
      out << why.str() << std::endl;
      return false;
    }



    template <int dim>
    void
    PhaseSweepRun<dim>::run()
    {
      FeRunSettings s        = settings;
      double        previous = std::numeric_limits<double>::quiet_NaN();
      // K_tangent per load of the last pass (world rank 0): the next
      // pass's noise floor is the change from it.
      std::vector<std::vector<double>> k_tangent;
      for (unsigned int pass = 0;; ++pass)
        {
          const auto         start  = Clock::now();
          unsigned int       finest = 0;
          const unsigned int level  = s.stage.mesh.contact_refinements;
          const double       ratio =
            sweep(s,
                  pass == 0 ? std::move(first) :
                              make_scene(groups.first_phase(groups.group()), s),
                  k_tangent,
                  finest);
          if (settings.stage.mesh.error.target_accuracy > 0 &&
              dealii::Utilities::MPI::this_mpi_process(comm) == 0)
            std::cout << "  target accuracy: pass " << pass + 1 << " took "
                      << std::setprecision(3) << seconds_since(start)
                      << " s, its finest contact level " << finest
                      << std::setprecision(6) << std::endl;
          if (!sweep_again(pass, level, finest + 1, ratio, previous))
            return;
          // The first pass's floor is the roughness, the later ones' the
          // change between passes: only the latter compare.
          previous =
            pass == 0 ? std::numeric_limits<double>::quiet_NaN() : ratio;
          // The next pass refines every phase one level beyond the finest
          // this one reached (the per-state target may have taken phases
          // to different levels): a true refinement of each phase, so the
          // change measures the mesh's part. Each state still estimates
          // its error; the target is met, the states being finer than
          // where they met it.
          s.stage.mesh.contact_refinements   = finest + 1;
          s.stage.mesh.error.target_accuracy = 0;
        }
    }



    template class PhaseSweepRun<2>;
    template class PhaseSweepRun<3>;
  } // namespace runs
} // namespace cycloid

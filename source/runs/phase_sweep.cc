#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include <cycloid/postprocess/report.h>
#include <cycloid/postprocess/solution_record.h>
#include <cycloid/runs/phase_sweep.h>

#include <chrono>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

namespace cycloid
{
  namespace runs
  {
    namespace
    {
      namespace u = results::units;
      using Clock = std::chrono::steady_clock;

      double
      seconds_since(const Clock::time_point start)
      {
        return std::chrono::duration<double>(Clock::now() - start).count();
      }

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
        SweepOutput(const FeRunSettings       &settings,
                    const std::vector<double> &angles,
                    const PhaseGroups         &groups,
                    const MPI_Comm             comm,
                    const Clock::time_point    start)
          : settings(settings)
          , angles(angles)
          , groups(groups)
          , loads(settings.loading.load_values())
          , n_states(angles.size() * loads.size())
          , start(start)
          , report(report_options(settings), comm)
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
      first = make_scene(groups.first_phase(groups.group()));
    }



    template <int dim>
    std::unique_ptr<stage::StageScene<dim>>
    PhaseSweepRun<dim>::make_scene(const unsigned int k) const
    {
      mesh::MeshRequest request = mesh_request(settings, angles[k]);
      // A one-group sweep rewrote stage.msh at every phase, leaving the last
      // phase's; groups would write it at the same time, so only the last
      // phase's scene writes it.
      if (k + 1 != angles.size())
        request.msh_file.clear();
      return std::make_unique<stage::StageScene<dim>>(settings.stage,
                                                      request,
                                                      groups.comm());
    }



    template <int dim>
    void
    PhaseSweepRun<dim>::run()
    {
      const auto     start = Clock::now();
      SweepOutput    output(settings, angles, groups, comm, start);
      StateCollector collector(groups, comm);
      // This group's solution files; world rank 0's record lists them all.
      postprocess::SolutionRecord pieces(settings.stage.output_directory,
                                         groups.comm(),
                                         false);
      const bool writer = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      const std::vector<double> loads = settings.loading.load_values();
      // Per load: the group's last phase's active set (the warm start of
      // its next phase).
      std::vector<stage::ActiveSetSnapshot<dim>> snapshots(loads.size());
      const unsigned int begin = groups.first_phase(groups.group()),
                         end   = groups.first_phase(groups.group() + 1);
      for (unsigned int k = begin; k < end; ++k)
        {
          auto scene = k == begin ? std::move(first) : make_scene(k);
          for (unsigned int t = 0; t < loads.size(); ++t)
            {
              results::StageState state =
                solve_load(*scene, snapshots[t], settings.loading, loads, t);
              state.step = k * loads.size() + t;
              // The files first: the record lists only files that exist.
              if (settings.write_solution &&
                  !cycle_zero(settings.loading, loads, t))
                scene->output_results(state.step, pieces);
              collector.submit(state);
              if (writer)
                output.take(collector.receive(false));
            }
        }
      const double busy = seconds_since(start);
      collector.finish(busy);
      if (!writer)
        return;
      while (!output.complete())
        output.take(collector.receive(true));
      output.finish(collector.busy_times(busy));
    }



    template class PhaseSweepRun<2>;
    template class PhaseSweepRun<3>;
  } // namespace runs
} // namespace cycloid

#include <deal.II/base/mpi.h>

#include <cycloid/postprocess/report.h>
#include <cycloid/postprocess/solution_record.h>
#include <cycloid/runs/phase_sweep.h>
#include <cycloid/runs/quasi_static.h>

#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace cycloid
{
  namespace runs
  {
    namespace u = results::units;

    mesh::MeshRequest
    mesh_request(const FeRunSettings &settings, const double psi)
    {
      mesh::MeshRequest request;
      request.crank_angle = psi;
      request.load_sign   = mesh::common_sign(settings.loading.load_values());
      if (settings.stage.mesh.write_msh)
        request.msh_file = settings.stage.output_directory + "/stage.msh";
      return request;
    }



    bool
    cycle_zero(const parameters::LoadingParameters &loading,
               const std::vector<double>           &loads,
               const unsigned int                   i)
    {
      return loading.torque_cycle && loads[i] == 0;
    }



    postprocess::Report::Options
    report_options(const FeRunSettings &settings)
    {
      postprocess::Report::Options options;
      options.directory        = settings.stage.output_directory;
      options.rotation_control = settings.loading.rotation_control;
      options.torque_cycle     = settings.loading.torque_cycle;
      options.rated_torque     = settings.loading.rated_torque;
      options.lost_motion_fraction =
        parameters::LoadingParameters::lost_motion_torque;
      return options;
    }



    template <int dim>
    const stage::StageSettings &
    QuasiStaticRun<dim>::announce(const FeRunSettings &settings,
                                  const MPI_Comm       comm)
    {
      if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        std::cout << "cycloid-contact: quasi-static FE contact, "
                  << stage::description(settings.stage) << ", crank angle "
                  << settings.loading.crank_angle_deg << " deg, "
                  << settings.loading.load_values().size()
                  << (settings.loading.rotation_control ? " rotation(s)" :
                                                          " torque(s)")
                  << std::endl;
      return settings.stage;
    }



    template <int dim>
    QuasiStaticRun<dim>::QuasiStaticRun(const FeRunSettings &settings,
                                        const MPI_Comm       comm)
      : settings(settings)
      , comm(comm)
      , scene(announce(settings, comm),
              mesh_request(settings, settings.loading.crank_angle()),
              comm)
    {}



    template <int dim>
    void
    QuasiStaticRun<dim>::run()
    {
      postprocess::Report         report(report_options(settings), comm);
      postprocess::SolutionRecord record(settings.stage.output_directory, comm);
      const std::vector<double>   loads = settings.loading.load_values();
      for (unsigned int step = 0; step < loads.size(); ++step)
        {
          const bool          limit = cycle_zero(settings.loading, loads, step);
          results::StageState state =
            limit ? scene.zero_torque_limit(
                      parameters::LoadingParameters::zero_side(loads, step)) :
                    scene.solve(loads[step]);
          state.step = step;
          report.write(state, loads[step]);
          report.print(state,
                       "  state " + std::to_string(step + 1) + "/" +
                         std::to_string(loads.size()) + ": ");
          // (A zero-torque limit has no field of its own.)
          if (settings.write_solution && !limit)
            scene.output_results(step, record);
        }
      report.finish();
      scene.print_timing();
    }



    template <int dim>
    PhaseSweepRun<dim>::PhaseSweepRun(const FeRunSettings &settings,
                                      const MPI_Comm       comm)
      : settings(settings)
      , comm(comm)
      , angles(settings.loading.crank_angles(
          geometry::CycloidGeometry(settings.stage.geometry).mesh_period()))
    {
      dealii::ConditionalOStream(
        std::cout, dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        << "cycloid-contact: phase sweep, FE contact, "
        << stage::description(settings.stage) << ", " << angles.size()
        << " crank angles over "
        << geometry::CycloidGeometry(settings.stage.geometry).mesh_period() *
             u::deg_per_rad
        << " deg x " << settings.loading.load_values().size() << " load(s)"
        << std::endl;
      first = std::make_unique<stage::StageScene<dim>>(
        settings.stage, mesh_request(settings, angles.front()), comm);
    }



    template <int dim>
    void
    PhaseSweepRun<dim>::run()
    {
      postprocess::Report         report(report_options(settings), comm);
      postprocess::SolutionRecord record(settings.stage.output_directory, comm);
      const std::vector<double>   loads    = settings.loading.load_values();
      const unsigned int          n_states = angles.size() * loads.size();
      // Per load: the last phase's active set (the warm start of the next).
      std::vector<stage::ActiveSetSnapshot<dim>> snapshots(loads.size());
      const auto   start = std::chrono::steady_clock::now();
      unsigned int step  = 0;
      for (unsigned int k = 0; k < angles.size(); ++k)
        {
          auto scene =
            k == 0 ? std::move(first) :
                     std::make_unique<stage::StageScene<dim>>(
                       settings.stage, mesh_request(settings, angles[k]), comm);
          for (unsigned int t = 0; t < loads.size(); ++t, ++step)
            {
              const bool limit = cycle_zero(settings.loading, loads, t);
              results::StageState state;
              if (limit)
                state = scene->zero_torque_limit(
                  parameters::LoadingParameters::zero_side(loads, t));
              else
                {
                  scene->warm_start(snapshots[t]);
                  state        = scene->solve(loads[t]);
                  snapshots[t] = scene->active_set_snapshot();
                }
              state.step           = step;
              const double elapsed = std::chrono::duration<double>(
                                       std::chrono::steady_clock::now() - start)
                                       .count();
              std::ostringstream prefix;
              prefix << "  phase " << k + 1 << "/" << angles.size()
                     << " (crank " << std::setprecision(5)
                     << angles[k] * u::deg_per_rad << " deg), elapsed "
                     << std::setprecision(3) << elapsed << " s, remaining ~"
                     << elapsed * (n_states - step - 1) / (step + 1)
                     << " s: " << std::setprecision(6);
              report.write(state, loads[t]);
              report.print(state, prefix.str());
              if (settings.write_solution && !limit)
                scene->output_results(step, record);
            }
        }
      report.finish();
    }



    template class QuasiStaticRun<2>;
    template class QuasiStaticRun<3>;
    template class PhaseSweepRun<2>;
    template class PhaseSweepRun<3>;
  } // namespace runs
} // namespace cycloid

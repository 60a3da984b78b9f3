#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <cycloid/postprocess/report.h>
#include <cycloid/postprocess/solution_record.h>
#include <cycloid/runs/quasi_static.h>

#include <cmath>
#include <iostream>

namespace cycloid
{
  namespace runs
  {
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



    double
    largest_load(const std::vector<double> &loads)
    {
      double largest = 0;
      for (const double x : loads)
        if (std::abs(x) > std::abs(largest))
          largest = x;
      return largest;
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
      options.directory = settings.stage.output_directory;
      options.allowable_pressure =
        settings.stage.material.allowable_contact_pressure;
      options.rotation_control = settings.loading.rotation_control;
      options.torque_cycle     = settings.loading.torque_cycle;
      options.rated_torque     = settings.loading.rated_torque;
      options.lost_motion_fraction =
        parameters::LoadingParameters::lost_motion_torque;
      const auto &m             = settings.stage.mesh;
      options.warning_threshold = m.error.warning_threshold;
      // Under a target the state has already refined as far as it was
      // allowed: the cure is to allow more cycles, or more memory where a
      // refinement would not have fitted (the state said so).
      options.refine_advice =
        m.error.target_accuracy > 0 ?
          "Cure: raise Mesh/Maximum accuracy cycles (now " +
            std::to_string(m.error.max_cycles) +
            ") or Mesh/Contact refinements (now " +
            std::to_string(m.contact_refinements) +
            ") so that Target accuracy (" +
            dealii::Utilities::to_string(m.error.target_accuracy) +
            ") can be reached; where a state's refinement stopped for "
            "memory, run it with more (more nodes) (doc/error-estimate.md)." :
          "Cure: raise Mesh/Contact refinements (now " +
            std::to_string(m.contact_refinements) +
            "), or set Mesh/Target accuracy (now 0) to the accuracy "
            "wanted (doc/error-estimate.md).";
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
      // The states' expected resolution at the largest torque, before
      // the user waits for the first (3D: minutes).
      scene.announce_resolution(largest_load(loads));
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
            {
              const std::string name = postprocess::SolutionRecord::name(step);
              scene.output_results(name);
              record.add(step, name + ".pvtu");
            }
        }
      report.finish();
      scene.print_timing();
    }



    template class QuasiStaticRun<2>;
    template class QuasiStaticRun<3>;
  } // namespace runs
} // namespace cycloid

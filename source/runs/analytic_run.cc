#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <cycloid/postprocess/report.h>
#include <cycloid/results/cost_figures.h>
#include <cycloid/runs/analytic_run.h>

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace cycloid
{
  namespace runs
  {
    namespace u = results::units;

    using results::seconds_since;



    bool
    show_state(const unsigned int k,
               const unsigned int n_k,
               const unsigned int t,
               const unsigned int n_t,
               const bool         always)
    {
      if (always || n_k * n_t <= 20)
        return true;
      if (n_t > 20)
        return (k == 0 || k + 1 == n_k) &&
               (t % (n_t / 20) == 0 || t + 1 == n_t);
      return k % std::max(1u, n_k / 10) == 0 || k + 1 == n_k;
    }



    void
    print_if_shown(const postprocess::Report &report,
                   const results::StageState &state,
                   const unsigned int         n_k,
                   const unsigned int         t,
                   const unsigned int         n_t,
                   const bool                 always)
    {
      if (show_state(state.step / n_t, n_k, t, n_t, always))
        report.print(state,
                     "  state " + std::to_string(state.step + 1) + "/" +
                       std::to_string(n_k * n_t) + ": ");
    }



    AnalyticRun::AnalyticRun(const Settings &settings, const MPI_Comm comm)
      : settings(settings)
      , comm(comm)
      , model(settings.model)
    {}



    void
    AnalyticRun::run()
    {
      postprocess::Report::Options options;
      options.directory = settings.output_directory;
      options.allowable_pressure =
        settings.model.material.allowable_contact_pressure;
      options.discretised  = false;
      options.bearings     = settings.model.bearings.needle();
      options.breakdown    = true;
      options.torque_cycle = settings.loading.torque_cycle;
      options.rated_torque = settings.loading.rated_torque;
      options.lost_motion_fraction =
        parameters::LoadingParameters::lost_motion_torque;
      postprocess::Report report(options, comm);
      // Every rank checked the geometry (so a bad prm fails everywhere
      // alike); only rank 0 computes and writes.
      if (dealii::Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      const auto               &geo = model.geometry();
      const std::vector<double> angles =
        settings.loading.crank_angles(geo.mesh_period());
      // Not load_values(): Control = rotation is for FE runs (a warning
      // names it, app/ignored_entries.h).
      const std::vector<double> torques  = settings.loading.torque_values();
      const unsigned int        n_states = angles.size() * torques.size();
      std::cout << "cycloid-contact: analytic model '"
                << model.pair_model().name()
                << "', zp = " << settings.model.geometry.n_pins
                << ", rp = " << geo.pin_circle_radius() << " mm, "
                << settings.model.scene.n_discs << " disc(s), " << angles.size()
                << " crank angle(s) x " << torques.size() << " torque(s)"
                << std::endl;

      unsigned int step    = 0;
      double       beta    = 0;
      double       total_s = 0;
      for (const double psi : angles)
        {
          // The unloaded geometry of a crank angle serves all its torques;
          // its cost goes to the first torque's wall time.
          auto       start      = std::chrono::steady_clock::now();
          const auto pins       = model.unloaded_pins(psi);
          double     geometry_s = seconds_since(start);
          for (unsigned int t = 0; t < torques.size(); ++t, ++step)
            {
              start = std::chrono::steady_clock::now();
              analytic::LoadState load;
              try
                {
                  // A torque cycle's zero is the limit of its branch.
                  load =
                    settings.loading.torque_cycle && torques[t] == 0 ?
                      model.zero_torque_limit(
                        pins,
                        parameters::LoadingParameters::zero_side(torques, t),
                        psi) :
                      model.solve(pins, torques[t], beta, psi);
                }
              catch (dealii::ExceptionBase &e)
                {
                  std::ostringstream info;
                  e.print_info(info);
                  AssertThrow(
                    false,
                    dealii::ExcMessage(
                      "state " + std::to_string(step) + " (crank angle " +
                      std::to_string(psi * u::deg_per_rad) + " deg, torque " +
                      std::to_string(torques[t]) + " N m): " + info.str()));
                }
              beta                      = load.rotation;
              results::StageState state = model.stage_state(load, psi);
              state.step                = step;
              state.wall_s              = seconds_since(start) + geometry_s;
              geometry_s                = 0;
              total_s += state.wall_s;
              // Only rank 0 computes (the others wait at the end).
              state.peak_memory_MB = results::peak_memory_MB(MPI_COMM_SELF);
              report.write(state, torques[t]);
              print_if_shown(report,
                             state,
                             angles.size(),
                             t,
                             torques.size(),
                             settings.loading.is_rated_state(torques[t]));
            }
        }
      report.finish();
      std::cout << "  compute time " << total_s * 1e3 << " ms for " << n_states
                << " states" << std::endl;
    }
  } // namespace runs
} // namespace cycloid

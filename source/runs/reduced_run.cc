#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <cycloid/postprocess/report.h>
#include <cycloid/reduced/reduced_model.h>
#include <cycloid/results/cost_figures.h>
#include <cycloid/results/error_estimate.h>
#include <cycloid/runs/analytic_run.h>
#include <cycloid/runs/reduced_run.h>
#include <cycloid/stage/cost_estimate.h>
#include <cycloid/stage/stage_scene.h>

#include <chrono>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

namespace cycloid
{
  namespace runs
  {
    namespace u = results::units;

    namespace
    {
      using results::Clock;
      using results::seconds_since;
    } // namespace



    template <int dim>
    ReducedRun<dim>::ReducedRun(const Settings &settings, const MPI_Comm comm)
      : settings(settings)
      , comm(comm)
      , model(settings.model.stage.model_settings())
    {}



    template <int dim>
    int
    ReducedRun<dim>::load_sign() const
    {
      return parameters::LoadingParameters::load_sign(
        settings.loading.torque_values());
    }



    template <int dim>
    postprocess::Report::Options
    ReducedRun<dim>::report_options() const
    {
      postprocess::Report::Options options;
      options.directory = settings.model.stage.output_directory;
      options.allowable_pressure =
        settings.model.stage.material.allowable_contact_pressure;
      // No contact mesh, so no mesh-to-mesh noise between crank angles:
      // the coarse model carries the far field only and its contact points
      // move smoothly over one mesh; the first and last phase of a period
      // differ by the crank holes, which stay with the disc (an FE sweep's
      // periodic meshes turn them by a pin pitch instead).
      options.discretised  = false;
      options.bearings     = settings.model.stage.bearings.needle();
      options.breakdown    = true;
      options.torque_cycle = settings.loading.torque_cycle;
      options.rated_torque = settings.loading.rated_torque;
      options.lost_motion_fraction =
        parameters::LoadingParameters::lost_motion_torque;
      const auto &s             = settings.model;
      options.warning_threshold = s.stage.mesh.error.warning_threshold;
      options.refine_advice =
        "Cure: a finer coarse model (Reduced/Contact refinements, now " +
        std::to_string(s.reduced.refinements(dim)) +
        ", or a smaller Mesh/Contact element size, now " +
        dealii::Utilities::to_string(s.stage.mesh.contact_size) + " mm)";
      return options;
    }



    template <int dim>
    void
    ReducedRun<dim>::announce_cost(const reduced::CoarseModel<dim> &coarse,
                                   const std::vector<double> &angles) const
    {
      const auto &s      = settings.model;
      const auto  slices = dim == 3 ? s.reduced.axial_slices : 1u;
      const analytic::StageModel model(s.stage.model_settings());
      const auto                 contacts = [&](const int sign) {
        return static_cast<unsigned int>(
          reduced::carrying_pins(model, angles.front(), sign).size() * slices);
      };
      const unsigned int       n_anchors = s.reduced.anchor_angles;
      stage::ReducedCostInputs in;
      in.dimension  = dim;
      in.n_dofs     = coarse.dofs();
      in.n_contacts = contacts(load_sign());
      in.n_condensations =
        n_anchors >= 2 && n_anchors < angles.size() ? n_anchors : angles.size();
      in.n_ranks          = dealii::Utilities::MPI::n_mpi_processes(comm);
      const auto estimate = stage::estimate_reduced_cost(in);
      if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        {
          std::cout << "  " << estimate.line() << std::endl;
          if (load_sign() == 0)
            std::cout << "  both flanks condensed (" << in.n_contacts
                      << " contacts instead of " << contacts(1)
                      << "): the torques have both signs (a torque cycle, "
                         "or negative torques in the list), so every pin "
                         "may touch either flank"
                      << std::endl;
        }
      stage::check_reduced_memory(estimate,
                                  stage::available_memory_bytes(comm),
                                  s.stage.mesh,
                                  slices);
    }



    template <int dim>
    std::unique_ptr<reduced::CompliancePath<dim>>
    ReducedRun<dim>::compliance_path(const reduced::ReducedSettings &s,
                                     reduced::CoarseModel<dim>      &coarse,
                                     const std::vector<double>      &angles,
                                     std::ostream                   *progress,
                                     const bool verbose) const
    {
      // A sweep of more crank angles than anchors condenses at the anchors
      // only and interpolates the compliance in between.
      const unsigned int n_anchors = s.reduced.anchor_angles;
      if (n_anchors < 2 || n_anchors >= angles.size())
        return nullptr;
      std::vector<double> anchors;
      for (unsigned int a = 0; a < n_anchors; ++a)
        anchors.push_back(angles.front() + (angles.back() - angles.front()) *
                                             a / (n_anchors - 1));
      if (verbose && dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        std::cout << "  condensing at " << n_anchors
                  << " anchor angles, interpolated over " << angles.size()
                  << " crank angles" << std::endl;
      return std::make_unique<reduced::CompliancePath<dim>>(
        s, coarse, anchors, angles, load_sign(), progress);
    }



    template <int dim>
    analytic::LoadState
    ReducedRun<dim>::solve_state(reduced::ReducedModel<dim> &phase,
                                 const std::vector<double>  &torques,
                                 const unsigned int          t,
                                 const double                crank_angle,
                                 const unsigned int          step,
                                 const double                beta) const
    {
      try
        {
          return settings.loading.torque_cycle && torques[t] == 0 ?
                   phase.zero_torque_limit(
                     parameters::LoadingParameters::zero_side(torques, t)) :
                   phase.solve(torques[t], beta);
        }
      catch (dealii::ExceptionBase &e)
        {
          std::ostringstream info;
          e.print_info(info);
          AssertThrow(false,
                      dealii::ExcMessage(
                        "state " + std::to_string(step) + " (crank angle " +
                        std::to_string(crank_angle * u::deg_per_rad) +
                        " deg, torque " + std::to_string(torques[t]) +
                        " N m): " + info.str()));
        }
      return {};
    }



    template <int dim>
    void
    ReducedRun<dim>::solve_states(
      const reduced::ReducedSettings                                 &s,
      reduced::CoarseModel<dim>                                      &coarse,
      const std::vector<double>                                      &angles,
      const bool                                                      verbose,
      const std::function<void(results::StageState &, unsigned int)> &visit)
      const
    {
      const bool root =
        verbose && dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      // A long condensation (3D) shows its progress.
      std::ostream *progress = root && dim == 3 ? &std::cout : nullptr;
      const std::vector<double> torques = settings.loading.torque_values();
      // wall_s: the work of the state after the mesh exists; a crank
      // angle's condensation (or an anchored sweep's, for the first state)
      // goes to the first state that needs it.
      auto         start = Clock::now();
      const auto   path = compliance_path(s, coarse, angles, progress, verbose);
      double       setup_s = seconds_since(start);
      unsigned int step    = 0;
      double       beta    = 0;
      for (unsigned int k = 0; k < angles.size(); ++k)
        {
          start            = Clock::now();
          const auto phase = path ?
                               std::make_unique<reduced::ReducedModel<dim>>(
                                 s, coarse, angles[k], load_sign(), *path) :
                               std::make_unique<reduced::ReducedModel<dim>>(
                                 s, coarse, angles[k], load_sign(), progress);
          setup_s += seconds_since(start);
          if (root && (k == 0 || show_state(k, angles.size(), 0, 1)))
            std::cout << "  crank angle " << angles[k] * u::deg_per_rad
                      << " deg: " << phase->n_contacts()
                      << (path ? " contacts interpolated in " :
                                 " contacts condensed in ")
                      << seconds_since(start) << " s (asymmetry "
                      << phase->compliance().asymmetry << ")" << std::endl;
          for (unsigned int t = 0; t < torques.size(); ++t, ++step)
            {
              start = Clock::now();
              const analytic::LoadState load =
                solve_state(*phase, torques, t, angles[k], step, beta);
              beta                      = load.rotation;
              results::StageState state = phase->stage_state(load);
              state.step                = step;
              state.wall_s              = seconds_since(start) + setup_s;
              setup_s                   = 0;
              visit(state, t);
            }
        }
    }



    template <int dim>
    std::vector<results::StageState>
    ReducedRun<dim>::companion_states(const reduced::CoarseModel<dim> &fine,
                                      const std::vector<double>       &angles,
                                      std::string &failure) const
    {
      const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      const reduced::ReducedSettings   s = settings.model.coarser();
      std::vector<results::StageState> states;
      try
        {
          reduced::CoarseModel<dim> coarse(s,
                                           angles.front(),
                                           angles.back() - angles.front(),
                                           load_sign(),
                                           comm);
          if (root)
            std::cout << "  error estimate: the same states on a coarser "
                      << "companion (" << settings.model.coarser_description()
                      << "), " << coarse.dofs() << " DoFs against "
                      << fine.dofs() << std::endl;
          const auto start = Clock::now();
          solve_states(s,
                       coarse,
                       angles,
                       false,
                       [&](results::StageState &state, unsigned int) {
                         states.push_back(state);
                       });
          if (root)
            std::cout << "  companion solved in " << seconds_since(start)
                      << " s" << std::endl;
        }
      catch (std::exception &e)
        {
          // The run goes on without an estimate for the states the
          // companion did not reach; they say why.
          failure        = e.what();
          const auto end = failure.find_last_not_of(" \n");
          failure.erase(end == std::string::npos ? 0 : end + 1);
          if (root)
            std::cout << "  error estimate: the companion model failed after "
                      << states.size() << " state(s): " << failure << std::endl;
        }
      return states;
    }



    template <int dim>
    void
    ReducedRun<dim>::run()
    {
      const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      const std::vector<double> angles =
        settings.loading.crank_angles(model.geometry().mesh_period());
      const std::vector<double> torques  = settings.loading.torque_values();
      const unsigned int        n_states = angles.size() * torques.size();
      if (root)
        std::cout << "cycloid-contact: reduced model, "
                  << stage::description(settings.model.stage)
                  << ", load half-width w = "
                  << settings.model.load_half_width() << " mm, "
                  << angles.size() << " crank angle(s) x " << torques.size()
                  << " torque(s)" << std::endl;

      const auto start = Clock::now();
      // One coarse model for every crank angle: meshed at the first, its
      // fine zones along the contact paths to the last.
      reduced::CoarseModel<dim> coarse(settings.model,
                                       angles.front(),
                                       angles.back() - angles.front(),
                                       load_sign(),
                                       comm);
      if (root)
        std::cout << "  coarse model: " << coarse.dofs() << " DoFs, built in "
                  << seconds_since(start) << " s" << std::endl;
      announce_cost(coarse, angles);
      // The files once the condensation is known to fit: a run stopped by
      // the memory check leaves none.
      postprocess::Report report(report_options(), comm);
      // The companion first, so that its factorisation is gone before the
      // run's own is made.
      std::string                            failure;
      const std::vector<results::StageState> companion =
        settings.model.reduced.error_estimate ?
          companion_states(coarse, angles, failure) :
          std::vector<results::StageState>();
      const std::string method =
        "against the companion, " + settings.model.coarser_description();
      solve_states(
        settings.model,
        coarse,
        angles,
        true,
        [&](results::StageState &state, const unsigned int t) {
          const unsigned int step = state.step;
          if (step < companion.size())
            {
              results::set_error_estimate(companion[step], state, method);
              // The coarse model's part, plus the near-field law's own.
              // (A torque cycle's zero-torque limits have no estimate.)
              if (state.error.available())
                results::add_model_error(
                  reduced::near_field_error(
                    state, settings.model.stage.geometry.pin_radius),
                  state);
              state.wall_s += companion[step].wall_s;
            }
          else if (settings.model.reduced.error_estimate)
            {
              state.error.method  = method;
              state.error.failure = failure;
            }
          state.peak_memory_MB = results::peak_memory_MB(comm);
          report.write(state, torques[t]);
          if (root)
            print_if_shown(report,
                           state,
                           angles.size(),
                           t,
                           torques.size(),
                           settings.loading.is_rated_state(torques[t]));
        });
      report.finish();
      if (root)
        {
          std::cout << "  reduced model: " << n_states << " states in "
                    << seconds_since(start) << " s; stages (all crank angles):";
          for (const auto &[name, t] : coarse.stage_times())
            std::cout << " " << name << " " << t << " s;";
          std::cout << std::endl;
        }
    }



    template class ReducedRun<2>;
    template class ReducedRun<3>;
  } // namespace runs
} // namespace cycloid

#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>

#include <cycloid/results/cost_figures.h>
#include <cycloid/runs/transient.h>

#include <chrono>
#include <cstdint>
#include <iostream>
#include <limits>
#include <sstream>

namespace cycloid
{
  namespace runs
  {
    namespace u = results::units;

    namespace
    {
      /** The settings after the checks a transient run needs before it
       * builds anything, with what the scheme tells the scene. */
      template <typename Settings>
      Settings
      checked(const Settings &s)
      {
        AssertThrow(s.run.stage.mesh.adaptive_cycles == 0,
                    dealii::ExcMessage(
                      "Run = transient keeps one mesh through the run: set "
                      "Mesh/Adaptive refinement cycles = 0 (the a-priori "
                      "Contact refinements follow the crank sweep)."));
        AssertThrow(s.run.loading.load_values().size() == 1,
                    dealii::ExcMessage(
                      "Run = transient: give one value of Loading/Torque (or "
                      "Loading/Rotation under rotation control) and keep "
                      "Loading/Torque cycle = false; the ramp is set by "
                      "Transient/Ramp time."));
        Settings c = s;
        // Newmark and generalized-alpha solve every step on one operator;
        // the contact-stabilised scheme alternates it with a projection.
        c.run.stage.one_operator =
          s.transient.scheme != dynamics::Scheme::contact_stabilised;
        return c;
      }

      /** The time scheme's settings. */
      dynamics::DynamicsSettings
      dynamics_settings(const dynamics::TransientParameters &t)
      {
        dynamics::DynamicsSettings d;
        d.scheme             = t.scheme;
        d.spectral_radius    = t.spectral_radius;
        d.rayleigh_mass      = t.rayleigh_mass;
        d.rayleigh_stiffness = t.rayleigh_stiffness;
        return d;
      }

      /** The label of step @p step in messages. */
      std::string
      step_label(const unsigned int step, const double time, const double psi)
      {
        std::ostringstream label;
        label << "step " << step << " (t = " << time << " s, crank angle "
              << psi * u::deg_per_rad << " deg)";
        return label.str();
      }
    } // namespace



    template <int dim>
    TransientRun<dim>::TransientRun(const Settings &settings,
                                    const MPI_Comm  comm)
      : settings(checked(settings))
      , comm(comm)
      , pcout(std::cout, dealii::Utilities::MPI::this_mpi_process(comm) == 0)
      , time(settings.transient,
             settings.run.loading.crank_angle(),
             settings.run.loading.load_values().front())
      , scene(
          this->settings.run.stage,
          [&] {
            auto request =
              mesh_request(settings.run, settings.run.loading.crank_angle());
            request.sweep = time.crank_sweep();
            return request;
          }(),
          comm)
      , energy(settings.transient.max_energy_error,
               settings.transient.scheme_name,
               time.crank_turns())
      , checkpoint(settings.run.stage.output_directory, comm)
      , series({settings.transient.scheme_name,
                settings.transient.time_step,
                settings.transient.crank_speed,
                settings.run.stage.geometry.n_pins,
                settings.run.stage.scene.n_discs})
      , record(settings.run.stage.output_directory, comm)
    {
      dynamics = std::make_unique<dynamics::ContactDynamics<dim>>(
        scene.contact_problem(), dynamics_settings(settings.transient));
    }



    template <int dim>
    double
    TransientRun<dim>::angular_momentum() const
    {
      const auto Mv =
        scene.contact_problem().elasticity().mass_times(dynamics->velocity());
      const auto &g = scene.rotation_field();
      double      L = 0;
      for (const auto i : g.locally_owned_elements())
        L += g[i] * Mv[i];
      return dealii::Utilities::MPI::sum(L, comm);
    }



    template <int dim>
    unsigned int
    TransientRun<dim>::start(std::vector<std::uintmax_t> &sizes)
    {
      if (!settings.transient.resume)
        {
          scene.place_discs(time.crank_angle(0.));
          dynamics->initialise();
          return 0;
        }
      unsigned int step = 0;
      double       t    = 0;
      auto         in   = checkpoint.open(step, t);
      scene.place_discs(time.crank_angle(t));
      dynamics->initialise();
      dynamics::CheckpointArchive ar(*in);
      checkpoint_fields(ar, sizes);
      checkpoint.check(*in);
      // The solution files written before the checkpoint.
      std::vector<std::pair<double, std::string>> previous;
      for (unsigned int s = 1; s <= step; ++s)
        if (time.output_due(s))
          previous.emplace_back(s,
                                postprocess::SolutionRecord::name(s) + ".pvtu");
      record.restore(previous);
      pcout << "  resumed from the checkpoint at step " << step
            << " (t = " << time.time(step) << " s)" << std::endl;
      return step;
    }



    template <int dim>
    void
    TransientRun<dim>::write_checkpoint(const unsigned int         step,
                                        const postprocess::Report &report)
    {
      dealii::TimerOutput::Scope scope(scene.timer(), "checkpoint");
      // CSV sizes at this step: a restart truncates the files to them.
      std::vector<std::uintmax_t> sizes = report.file_sizes();
      checkpoint.write(step, time.time(step), [&](std::ostream &out) {
        dynamics::CheckpointArchive ar(out);
        checkpoint_fields(ar, sizes);
      });
    }



    template <int dim>
    void
    TransientRun<dim>::checkpoint_fields(dynamics::CheckpointArchive &ar,
                                         std::vector<std::uintmax_t> &sizes)
    {
      dynamics->checkpoint(ar);
      energy.checkpoint(ar);
      series.checkpoint(ar);
      ar.array(sizes);
    }



    template <int dim>
    std::pair<results::StageState, results::EnergyState>
    TransientRun<dim>::advance(const unsigned int step)
    {
      const auto   step_start = std::chrono::steady_clock::now();
      const double t          = time.time(step);
      const double psi        = time.crank_angle(t);
      if (time.crank_turns())
        scene.place_discs(psi);
      const double         value    = time.load(t);
      const bool           rotation = settings.run.loading.rotation_control;
      dynamics::StepReport report;
      {
        dealii::TimerOutput::Scope scope(scene.timer(), "time step");
        report = dynamics->step(time.time_step(),
                                !rotation,
                                rotation ? value : scene.model_torque(value),
                                step_label(step, t, psi));
      }
      results::StageState s = scene.state(report.state, value);
      s.step                = step;
      s.k_tangent           = std::numeric_limits<double>::quiet_NaN();
      s.iterations          = report.iterations;
      s.linear_iterations   = report.state.linear_iterations;
      s.peak_memory_MB      = results::peak_memory_MB(comm);
      s.wall_s              = std::chrono::duration<double>(
                   std::chrono::steady_clock::now() - step_start)
                   .count();
      const double to_J  = scene.width_scale() * u::Nm_per_Nmm;
      auto         e     = energy.account(report, to_J, step, t);
      e.angular_momentum = angular_momentum() * to_J;
      return {s, e};
    }



    template <int dim>
    void
    TransientRun<dim>::print_progress(const unsigned int          step,
                                      const unsigned int          first,
                                      const results::StageState  &s,
                                      const results::EnergyState &e,
                                      const double                elapsed) const
    {
      const double remaining =
        elapsed / (step - first) * (time.last_step() - step);
      pcout << "  step " << step << "/" << time.n_steps() << ": t " << e.time_s
            << " s, crank " << s.crank * u::deg_per_rad << " deg, T "
            << s.torque << " N m, beta " << s.rotation << " rad, pins "
            << s.pins_in_contact() << ", iterations " << s.iterations
            << ", E_kin+E_el " << e.kinetic + e.elastic << " J, balance error "
            << e.balance << " J, " << elapsed << " s elapsed, ~" << remaining
            << " s left" << std::endl;
    }



    template <int dim>
    void
    TransientRun<dim>::run()
    {
      const auto                 &t     = settings.transient;
      const auto                 &dir   = settings.run.stage.output_directory;
      const auto                  begin = std::chrono::steady_clock::now();
      std::vector<std::uintmax_t> sizes;
      const unsigned int          first   = start(sizes);
      auto                        options = report_options(settings.run);
      options.energy                      = true;
      options.fluctuation                 = false;
      options.resume                      = t.resume;
      options.resume_sizes                = sizes;
      postprocess::Report report(options, comm);
      pcout << "  transient: " << t.scheme_name << ", dt " << t.time_step
            << " s, " << time.n_steps() << " steps to "
            << time.time(time.n_steps()) << " s, crank speed " << t.crank_speed
            << " deg/s" << std::endl;
      // The steps keep one mesh and carry no nested estimate: say at once
      // how well it resolves the contacts at the run's final torque.
      scene.announce_resolution(time.load(time.time(time.n_steps())));

      for (unsigned int step = first + 1; step <= time.last_step(); ++step)
        {
          const auto [state, e] = advance(step);
          report.write(state, state.torque);
          report.write(e, state);
          energy.check(e, step_label(step, e.time_s, state.crank), pcout);
          if (state.cycles_broken > 0)
            pcout << "  note: the active set cycled " << state.cycles_broken
                  << " time(s) at " << step_label(step, e.time_s, state.crank)
                  << "; the union of each cycle's sets was taken (largest "
                     "tension left "
                  << state.cycle_tension
                  << " of the largest nodal force; doc/stability.md, "
                     "\"Active-set cycling\")"
                  << std::endl;
          series.add(state, e);
          if (time.output_due(step))
            {
              const std::string name = postprocess::SolutionRecord::name(step);
              scene.output_results(name);
              record.add(step, name + ".pvtu");
            }
          if (time.checkpoint_due(step))
            {
              write_checkpoint(step, report);
              dealii::TimerOutput::Scope scope(scene.timer(), "hdf5");
              series.write_hdf5(dir, comm);
            }
          if (time.progress_due(step, first))
            print_progress(step,
                           first,
                           state,
                           e,
                           std::chrono::duration<double>(
                             std::chrono::steady_clock::now() - begin)
                             .count());
        }
      {
        dealii::TimerOutput::Scope scope(scene.timer(), "hdf5");
        series.write_hdf5(dir, comm);
      }
      if (time.last_step() < time.n_steps())
        pcout << "  stopped after step " << time.last_step()
              << " (Transient/Stop after step)" << std::endl;
      report.finish(); // the most loaded pin and the files written
      scene.print_timing();
    }



    template class TransientRun<2>;
    template class TransientRun<3>;
  } // namespace runs
} // namespace cycloid

#include <deal.II/base/exceptions.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>

#include <cycloid/analytic/stage_model.h>
#include <cycloid/app/run.h>
#include <cycloid/postprocess/result_writer.h>

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <map>

namespace cycloid
{
  namespace app
  {
    void
    run(const parameters::AllParameters &prm, const MPI_Comm comm)
    {
      using Mode = parameters::RunParameters::Mode;
      switch (prm.run.mode)
        {
          case Mode::analytic:
            run_analytic(prm, comm);
            return;
          case Mode::quasi_static:
            run_quasi_static(prm, comm);
            return;
          case Mode::phase_sweep:
            run_phase_sweep(prm, comm);
            return;
          case Mode::transient:
            run_transient(prm, comm);
            return;
          case Mode::mesh:
            if (prm.scene.dimension == 2)
              run_mesh<2>(prm, comm);
            else
              run_mesh<3>(prm, comm);
            return;
          default:
            AssertThrow(
              false,
              dealii::ExcMessage(
                "Run = " + prm.run.mode_name +
                " is not available in this version: Run = "
                "analytic, mesh, quasi-static, phase-sweep and transient are implemented (the rest is tracked in "
                "the project's issues)."));
        }
    }



    void
    run_analytic(const parameters::AllParameters &prm, const MPI_Comm comm)
    {
      // Every rank validates the geometry (so a bad prm fails everywhere
      // alike); only rank 0 computes and writes.
      const analytic::StageModel model(prm);
      if (dealii::Utilities::MPI::this_mpi_process(comm) != 0)
        return;

      const double              to_deg = 180. / dealii::numbers::PI;
      const auto               &geo    = model.geometry();
      const std::vector<double> angles =
        prm.loading.crank_angles(geo.mesh_period());
      const std::vector<double> &torques = prm.loading.torques;

      std::cout << "cycloid-contact: analytic model '"
                << model.pair_model().name()
                << "', zp = " << prm.geometry.n_pins
                << ", rp = " << geo.pin_circle_radius() << " mm, "
                << prm.scene.n_discs << " disc(s), " << angles.size()
                << " crank angle(s) x " << torques.size() << " torque(s)"
                << std::endl;

      postprocess::ResultWriter writer(prm.run.output_directory, true);

      // K_tangent per torque over the phases, for the summary.
      std::map<unsigned int, std::vector<double>> k_by_torque;
      unsigned int                                step    = 0;
      double                                      beta    = 0;
      double                                      total_s = 0;
      const unsigned int n_states = angles.size() * torques.size();
      for (const double psi : angles)
        {
          // The unloaded geometry of a crank angle serves all its torques.
          auto start = std::chrono::steady_clock::now();
          const std::vector<analytic::PinLoad> pins = model.unloaded_pins(psi);
          double geometry_s = std::chrono::duration<double>(
                                std::chrono::steady_clock::now() - start)
                                .count();
          for (unsigned int t = 0; t < torques.size(); ++t, ++step)
            {
              start = std::chrono::steady_clock::now();
              analytic::LoadState state;
              try
                {
                  state = model.solve(pins, torques[t], beta);
                }
              catch (dealii::ExceptionBase &e)
                {
                  std::ostringstream info;
                  e.print_info(info);
                  AssertThrow(
                    false,
                    dealii::ExcMessage(
                      "state " + std::to_string(step) + " (crank angle " +
                      std::to_string(psi * to_deg) + " deg, torque " +
                      std::to_string(torques[t]) + " N m): " + info.str()));
                }
              // wall_s: this state's solve plus (for the first torque) the
              // geometry of its crank angle.
              const double wall = std::chrono::duration<double>(
                                    std::chrono::steady_clock::now() - start)
                                    .count() +
                                  geometry_s;
              geometry_s = 0;
              total_s += wall;
              beta = state.rotation;

              postprocess::StiffnessRow row;
              row.step            = step;
              row.crank_deg       = psi * to_deg;
              row.torque_Nm       = state.torque;
              row.rotation_rad    = state.rotation;
              row.k_secant        = state.k_secant();
              row.k_tangent       = state.k_tangent;
              row.pins_in_contact = state.pins_in_contact;
              row.iterations      = state.iterations;
              row.dofs            = 0;
              row.wall_s          = wall;
              {
                dealii::Utilities::System::MemoryStats stats;
                dealii::Utilities::System::get_memory_stats(stats);
                row.peak_memory_MB = stats.VmHWM / 1024.; // rank 0 only
              }
              row.takeup_rad         = state.takeup;
              row.k_secant_elastic   = state.k_secant_elastic();
              row.reaction_torque_Nm = state.reaction_torque;

              std::vector<postprocess::PinForceRow> rows;
              rows.reserve(state.pins.size());
              for (const analytic::PinLoad &p : state.pins)
                {
                  postprocess::PinForceRow r;
                  r.step      = step;
                  r.crank_deg = row.crank_deg;
                  r.disc      = p.contact.disc;
                  r.pin       = p.contact.pin;
                  r.fx_N =
                    -p.force * p.contact.normal[0] + 0.; // no -0 in the CSV
                  r.fy_N         = -p.force * p.contact.normal[1] + 0.;
                  r.fn_N         = p.force;
                  r.arm_mm       = p.contact.arm;
                  r.clearance_um = p.contact.clearance * 1e3;
                  r.phase_deg    = p.contact.phase * to_deg;
                  r.approach_um  = p.approach * 1e3;
                  r.pair_stiffness_N_per_mm = p.stiffness;
                  r.contact_x_mm            = p.contact.contact_point[0];
                  r.contact_y_mm            = p.contact.contact_point[1];
                  r.hertz_halfwidth_um =
                    1e3 * analytic::hertz_half_width(
                            p.force,
                            prm.geometry.tooth_width,
                            prm.geometry.pin_radius,
                            p.contact.curvature_radius,
                            prm.material.disc.plane_strain_modulus(),
                            prm.scene.pins ==
                                parameters::SceneParameters::PinModel::rigid ?
                              0. :
                              prm.material.pin.plane_strain_modulus());
                  r.contact_halfwidth_um = r.hertz_halfwidth_um;
                  row.max_pin_force_N = std::max(row.max_pin_force_N, p.force);
                  rows.push_back(r);
                }
              writer.write(row, rows);
              k_by_torque[t].push_back(state.k_tangent);

              if (n_states <= 20 || step % std::max(1u, n_states / 10) == 0 ||
                  step + 1 == n_states)
                std::cout << "  state " << step + 1 << "/" << n_states
                          << ": crank " << std::setprecision(5) << row.crank_deg
                          << " deg, T " << state.torque << " N m, beta "
                          << std::setprecision(6) << state.rotation
                          << " rad, K_tangent " << state.k_tangent
                          << " N m/rad ("
                          << state.k_tangent * postprocess::rad_per_arcmin
                          << " N m/arcmin), pins " << state.pins_in_contact
                          << std::endl;
            }
        }

      if (angles.size() > 1)
        for (const auto &[t, ks] : k_by_torque)
          {
            const auto [lo, hi] = std::minmax_element(ks.begin(), ks.end());
            double mean         = 0;
            for (const double k : ks)
              mean += k;
            mean /= ks.size();
            std::cout << "  torque " << torques[t]
                      << " N m: K_tangent over the period min " << *lo
                      << ", max " << *hi << ", mean " << mean
                      << " N m/rad; fluctuation (max-min)/mean "
                      << (*hi - *lo) / mean << std::endl;
          }
      std::cout << "  compute time " << total_s * 1e3 << " ms for " << n_states
                << " states; results in " << prm.run.output_directory
                << "/stiffness.csv, pin_forces.csv" << std::endl;
    }
  } // namespace app
} // namespace cycloid

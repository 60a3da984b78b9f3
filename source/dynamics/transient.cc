#include <deal.II/base/exceptions.h>

#include <deal.II/base/hdf5.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>

#include <deal.II/lac/full_matrix.h>

#include <cycloid/dynamics/transient.h>
#include <cycloid/postprocess/result_writer.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace cycloid
{
  namespace dynamics
  {
    namespace
    {
      constexpr double deg = dealii::numbers::PI / 180.;

      std::string
      energy_header()
      {
        return "step,time_s,kinetic_J,elastic_J,external_work_J,"
               "active_set_iterations,crank_deg,torque_Nm,rotation_rad,"
               "bore_work_J,contact_work_J,dissipated_J,balance_error_J,"
               "relative_balance_error,max_penetration_um,wall_s,"
               "angular_momentum_Nms";
      }

      /** Byte size of a file (0 if missing). */
      std::uintmax_t
      size_of(const std::string &file)
      {
        std::error_code ec;
        const auto      n = std::filesystem::file_size(file, ec);
        return ec ? 0 : n;
      }
    } // namespace



    template <int dim>
    std::vector<std::vector<double> *>
    Transient<dim>::History::all()
    {
      return {&time,
              &crank_deg,
              &torque,
              &rotation,
              &k_secant,
              &kinetic,
              &elastic,
              &external_work,
              &dissipated,
              &balance,
              &penetration,
              &iterations,
              &angular_momentum,
              &fx,
              &fy,
              &fn};
    }



    template <int dim>
    Transient<dim>::Transient(const parameters::AllParameters &parameters,
                              const MPI_Comm                   comm)
      : contact::QuasiStatic<dim>(parameters,
                                  parameters.loading.crank_angle_deg * deg,
                                  comm,
                                  parameters.transient.crank_speed * deg *
                                    parameters.transient.end_time)
      , psi0(parameters.loading.crank_angle_deg * deg)
    {
      const auto &t = this->prm.transient;
      AssertThrow(this->prm.mesh.adaptive_cycles == 0,
                  dealii::ExcMessage(
                    "Run = transient keeps one mesh through the run: set "
                    "Mesh/Adaptive refinement cycles = 0 (the a-priori "
                    "Contact refinements follow the crank sweep)."));
      AssertThrow(this->prm.loading.load_values().size() == 1,
                  dealii::ExcMessage(
                    "Run = transient: give one value of Loading/Torque (or "
                    "Loading/Rotation under rotation control); the ramp is "
                    "set by Transient/Ramp time."));
      AssertThrow(t.end_time >= t.time_step,
                  dealii::ExcMessage(
                    "Transient/End time must be at least one Time step."));
      DynamicsSettings settings;
      settings.scheme             = parse_scheme(t.scheme);
      settings.spectral_radius    = t.spectral_radius;
      settings.rayleigh_mass      = t.rayleigh_mass;
      settings.rayleigh_stiffness = t.rayleigh_stiffness;
      dynamics =
        std::make_unique<ContactDynamics<dim>>(*this->contact, settings);

      // The discs' rigid rotation about their centres (mesh frame).
      const auto                   &el = this->contact->elasticity();
      const auto                   &fe = el.finite_element();
      const dealii::Quadrature<dim> nodes(
        fe.base_element(0).get_unit_support_points());
      dealii::FEValues<dim>                        values(el.mapping(),
                                   fe,
                                   nodes,
                                   dealii::update_quadrature_points);
      std::vector<dealii::types::global_dof_index> indices(
        fe.n_dofs_per_cell());
      rotation_field.reinit(el.locally_owned_dofs(), this->comm);
      for (const auto &cell : el.dof_handler().active_cell_iterators())
        {
          if (!cell->is_locally_owned() ||
              cell->material_id() >= this->prm.scene.n_discs)
            continue;
          const dealii::Point<2> c =
            this->geo.disc_centre(cell->material_id(), psi0);
          values.reinit(cell);
          cell->get_dof_indices(indices);
          for (unsigned int i = 0; i < indices.size(); ++i)
            {
              if (!el.locally_owned_dofs().is_element(indices[i]))
                continue;
              const auto [comp, node]    = fe.system_to_component_index(i);
              const auto &x              = values.quadrature_point(node);
              rotation_field[indices[i]] = comp == 0 ? -(x[1] - c[1]) :
                                           comp == 1 ? x[0] - c[0] :
                                                       0.;
            }
        }
      rotation_field.compress(dealii::VectorOperation::insert);
    }



    template <int dim>
    double
    Transient<dim>::angular_momentum() const
    {
      const auto Mv =
        this->contact->elasticity().mass_times(dynamics->velocity());
      double L = 0;
      for (const auto i : rotation_field.locally_owned_elements())
        L += rotation_field[i] * Mv[i];
      return dealii::Utilities::MPI::sum(L, this->comm);
    }



    template <int dim>
    void
    Transient<dim>::place_discs(const double psi_now)
    {
      dealii::TimerOutput::Scope scope(this->timer, "place discs");
      this->psi              = psi_now;
      const auto        &geo = this->geo;
      const unsigned int nd  = this->prm.scene.n_discs;
      const double       p0  = psi0;
      this->contact->set_placement(
        [&geo, nd, p0, psi_now](const dealii::types::material_id body,
                                const dealii::Point<dim>        &x) {
          if (body >= nd)
            return x;
          const dealii::Point<2> moved =
            geo.to_housing(body,
                           psi_now,
                           geo.to_disc(body, p0, dealii::Point<2>(x[0], x[1])));
          dealii::Point<dim> y = x;
          y[0]                 = moved[0];
          y[1]                 = moved[1];
          return y;
        });
      this->contact->update_geometry();
    }



    template <int dim>
    double
    Transient<dim>::load_at(const double t) const
    {
      const double tr    = this->prm.transient.ramp_time;
      const double value = this->prm.loading.load_values().front();
      if (tr <= 0 || t >= tr)
        return value;
      return value * 0.5 * (1. - std::cos(dealii::numbers::PI * t / tr));
    }



    template <int dim>
    void
    Transient<dim>::run()
    {
      const auto &t   = this->prm.transient;
      const auto &dir = this->prm.run.output_directory;
      const bool  root =
        dealii::Utilities::MPI::this_mpi_process(this->comm) == 0;
      const double       dt = t.time_step;
      const unsigned int n_steps =
        static_cast<unsigned int>(std::llround(t.end_time / dt));
      const bool         rotation = this->prm.loading.rotation_control;
      const double       scale    = this->width_scale();
      const unsigned int zp       = this->prm.geometry.n_pins;
      const unsigned int nd       = this->prm.scene.n_discs;
      const auto         start    = std::chrono::steady_clock::now();

      unsigned int first = 0;
      if (t.resume)
        {
          first = read_checkpoint();
          this->pcout << "  resumed from the checkpoint at step " << first
                      << " (t = " << first * dt << " s)" << std::endl;
        }
      else
        {
          place_discs(psi0);
          dynamics->initialise();
          if (root)
            {
              std::ofstream(dir + "/energy.csv") << energy_header() << '\n';
              std::ofstream(dir + "/stiffness.csv")
                << postprocess::ResultWriter::stiffness_header() << '\n';
              std::ofstream(dir + "/pin_forces.csv")
                << postprocess::ResultWriter::pin_forces_header() << '\n';
            }
        }
      std::ofstream energy, stiffness, pin_forces;
      if (root)
        {
          energy.open(dir + "/energy.csv", std::ios::app);
          stiffness.open(dir + "/stiffness.csv", std::ios::app);
          pin_forces.open(dir + "/pin_forces.csv", std::ios::app);
          for (auto *f : {&energy, &stiffness, &pin_forces})
            *f << std::setprecision(12);
        }
      this->pcout << "  transient: " << t.scheme << ", dt " << dt << " s, "
                  << n_steps << " steps to " << n_steps * dt
                  << " s, crank speed " << t.crank_speed << " deg/s"
                  << std::endl;

      bool               warned = false;
      const unsigned int last =
        t.stop_after_step > 0 ? std::min(t.stop_after_step, n_steps) : n_steps;
      for (unsigned int step = first + 1; step <= last; ++step)
        {
          const auto   step_start = std::chrono::steady_clock::now();
          const double time       = step * dt;
          const double psi_now    = psi0 + t.crank_speed * deg * time;
          if (t.crank_speed != 0.)
            place_discs(psi_now);
          const double       value = load_at(time);
          std::ostringstream label;
          label << "step " << step << " (t = " << time << " s, crank angle "
                << psi_now / deg << " deg)";
          StepReport report;
          {
            dealii::TimerOutput::Scope scope(this->timer, "time step");
            report =
              rotation ?
                dynamics->step(dt, false, value, label.str()) :
                dynamics->step(dt, true, value * 1e3 / scale, label.str());
          }
          const double torque =
            rotation ? report.state.reaction * scale * 1e-3 : value;

          postprocess::StiffnessRow             row;
          std::vector<postprocess::PinForceRow> pins;
          this->pin_forces(torque, report.state, row, pins);
          row.step              = step;
          row.crank_deg         = psi_now / deg;
          row.k_tangent         = std::numeric_limits<double>::quiet_NaN();
          row.iterations        = report.iterations;
          row.linear_iterations = report.state.linear_iterations;
          row.peak_memory_MB    = postprocess::peak_memory_MB(this->comm);
          row.wall_s            = std::chrono::duration<double>(
                         std::chrono::steady_clock::now() - step_start)
                         .count();
          if (step == 1 && !t.resume)
            initial_energy = 0.;
          const double J        = scale * 1e-3;
          const double external = (report.bore_work + report.contact_work) * J;
          const double total =
            (report.kinetic + report.elastic + report.dissipated) * J;
          const double balance = total - external - initial_energy;
          // Relative to the largest energy level reached so far (the net
          // work falls while the stage swings back, so it cannot be the
          // scale).
          energy_scale = std::max({energy_scale, std::abs(external), total});
          const double relative = balance / std::max(energy_scale, 1e-300);

          const double L = angular_momentum() * J;
          if (root)
            {
              energy << step << ',' << time << ',' << report.kinetic * J << ','
                     << report.elastic * J << ',' << external << ','
                     << report.iterations << ',' << row.crank_deg << ','
                     << torque << ',' << report.state.beta << ','
                     << report.bore_work * J << ',' << report.contact_work * J
                     << ',' << report.dissipated * J << ',' << balance << ','
                     << relative << ',' << report.max_penetration * 1e3 << ','
                     << row.wall_s << ',' << L << '\n';
              energy.flush();
              postprocess::write_stiffness_row(stiffness, row);
              for (auto &p : pins)
                {
                  p.step      = step;
                  p.crank_deg = row.crank_deg;
                  postprocess::write_pin_force_row(pin_forces, p);
                }
              stiffness.flush();
              pin_forces.flush();
            }
          // The energy balance is the stability test: a scheme that chatters
          // at contact gains energy (plain Newmark) and its forces are then
          // wrong. Stop with a message rather than write such numbers on.
          if (std::abs(relative) > 0.05 && !warned && energy_scale > 0)
            {
              warned = true;
              this->pcout
                << "  warning: energy balance error " << 100. * relative
                << " % of the largest energy level at step " << step
                << (t.crank_speed != 0. ?
                      " (with the crank turning this includes the time "
                      "discretisation of the moving contacts; a smaller Time "
                      "step reduces it, see doc/stability.md)" :
                      "")
                << std::endl;
            }
          AssertThrow(std::abs(relative) <= t.max_energy_error ||
                        energy_scale <= 0,
                      dealii::ExcMessage(
                        "transient: the energy balance error reached " +
                        std::to_string(100. * relative) +
                        " % of the largest energy level at " + label.str() +
                        " (Transient/Maximum energy error " +
                        std::to_string(100. * t.max_energy_error) +
                        " %): the time integration does not keep the energy "
                        "balance (Scheme = " +
                        t.scheme +
                        "). Plain Newmark chatters at contact: use Scheme = "
                        "contact-stabilised or generalized-alpha; with the "
                        "crank turning, a smaller Time step reduces the "
                        "moving-contact share. The rows written so far are "
                        "valid."));
          history.time.push_back(time);
          history.crank_deg.push_back(row.crank_deg);
          history.torque.push_back(torque);
          history.rotation.push_back(report.state.beta);
          history.k_secant.push_back(row.k_secant);
          history.kinetic.push_back(report.kinetic * J);
          history.elastic.push_back(report.elastic * J);
          history.external_work.push_back(external);
          history.dissipated.push_back(report.dissipated * J);
          history.balance.push_back(balance);
          history.penetration.push_back(report.max_penetration * 1e3);
          history.iterations.push_back(report.iterations);
          history.angular_momentum.push_back(L);
          for (unsigned int k = 0; k < nd * zp; ++k)
            {
              history.fx.push_back(pins[k].fx_N);
              history.fy.push_back(pins[k].fy_N);
              history.fn.push_back(pins[k].fn_N);
            }

          if (t.output_interval > 0 && step % t.output_interval == 0)
            this->output_results(step, records);
          if (t.checkpoint_interval > 0 && step % t.checkpoint_interval == 0)
            {
              write_checkpoint(step, time);
              write_hdf5();
            }
          if (step == first + 1 || step % 10 == 0 || step == last)
            {
              const double elapsed = std::chrono::duration<double>(
                                       std::chrono::steady_clock::now() - start)
                                       .count();
              const double remaining = elapsed / (step - first) * (last - step);
              this->pcout << "  step " << step << "/" << n_steps << ": t "
                          << time << " s, crank " << row.crank_deg << " deg, T "
                          << torque << " N m, beta " << report.state.beta
                          << " rad, pins " << row.pins_in_contact
                          << ", iterations " << report.iterations
                          << ", E_kin+E_el "
                          << (report.kinetic + report.elastic) * J
                          << " J, balance error " << balance << " J, "
                          << elapsed << " s elapsed, ~" << remaining
                          << " s left" << std::endl;
            }
        }
      write_hdf5();
      if (last < n_steps)
        this->pcout << "  stopped after step " << last
                    << " (Transient/Stop after step)" << std::endl;
      this->print_timing();
    }



    template <int dim>
    void
    Transient<dim>::write_checkpoint(const unsigned int step,
                                     const double       time) const
    {
      dealii::TimerOutput::Scope scope(this->timer, "checkpoint");
      const auto                &dir = this->prm.run.output_directory;
      const unsigned int         rank =
        dealii::Utilities::MPI::this_mpi_process(this->comm);
      const unsigned int n_ranks =
        dealii::Utilities::MPI::n_mpi_processes(this->comm);
      const std::string name =
        dir + "/checkpoint.rank-" + std::to_string(rank) + ".bin";
      {
        std::ofstream       out(name + ".tmp", std::ios::binary);
        const std::uint64_t header[3] = {step, n_ranks, rank};
        out.write(reinterpret_cast<const char *>(header), sizeof(header));
        out.write(reinterpret_cast<const char *>(&time), sizeof(double));
        out.write(reinterpret_cast<const char *>(&initial_energy),
                  sizeof(double));
        out.write(reinterpret_cast<const char *>(&energy_scale),
                  sizeof(double));
        dynamics->save(out);
        auto &h = const_cast<History &>(history);
        for (const auto *v : h.all())
          {
            const std::uint64_t n = v->size();
            out.write(reinterpret_cast<const char *>(&n), sizeof(n));
            out.write(reinterpret_cast<const char *>(v->data()),
                      n * sizeof(double));
          }
        const std::uint64_t n_records = records.size();
        out.write(reinterpret_cast<const char *>(&n_records),
                  sizeof(n_records));
        // CSV sizes at this step: a restart truncates the files to them.
        for (const char *f : {"energy.csv", "stiffness.csv", "pin_forces.csv"})
          {
            const std::uint64_t n = size_of(dir + "/" + f);
            out.write(reinterpret_cast<const char *>(&n), sizeof(n));
          }
        AssertThrow(out,
                    dealii::ExcMessage("checkpoint: cannot write " + name));
      }
      // All ranks done before any file replaces the previous checkpoint.
      dealii::Utilities::MPI::sum(1, this->comm);
      std::filesystem::rename(name + ".tmp", name);
    }



    template <int dim>
    unsigned int
    Transient<dim>::read_checkpoint()
    {
      const auto        &dir = this->prm.run.output_directory;
      const unsigned int rank =
        dealii::Utilities::MPI::this_mpi_process(this->comm);
      const unsigned int n_ranks =
        dealii::Utilities::MPI::n_mpi_processes(this->comm);
      const std::string name =
        dir + "/checkpoint.rank-" + std::to_string(rank) + ".bin";
      std::ifstream in(name, std::ios::binary);
      AssertThrow(in,
                  dealii::ExcMessage(
                    "Transient/Resume: no checkpoint " + name +
                    " (set Transient/Checkpoint interval in the run to "
                    "resume, and the same Output directory)."));
      std::uint64_t header[3];
      double        time;
      in.read(reinterpret_cast<char *>(header), sizeof(header));
      in.read(reinterpret_cast<char *>(&time), sizeof(double));
      in.read(reinterpret_cast<char *>(&initial_energy), sizeof(double));
      in.read(reinterpret_cast<char *>(&energy_scale), sizeof(double));
      AssertThrow(in && header[1] == n_ranks && header[2] == rank,
                  dealii::ExcMessage(
                    "Transient/Resume: the checkpoint was written by " +
                    std::to_string(header[1]) +
                    " MPI rank(s); resume on the same number of ranks."));
      const unsigned int step = header[0];
      place_discs(psi0 + this->prm.transient.crank_speed * deg * time);
      dynamics->initialise();
      dynamics->load(in);
      for (auto *v : history.all())
        {
          std::uint64_t n;
          in.read(reinterpret_cast<char *>(&n), sizeof(n));
          v->resize(n);
          in.read(reinterpret_cast<char *>(v->data()), n * sizeof(double));
        }
      std::uint64_t n_records;
      in.read(reinterpret_cast<char *>(&n_records), sizeof(n_records));
      records.clear();
      const unsigned int every = this->prm.transient.output_interval;
      for (unsigned int s = 1; s <= step && every > 0; ++s)
        if (s % every == 0)
          records.emplace_back(
            s, "solution-" + dealii::Utilities::int_to_string(s, 4) + ".pvtu");
      std::uint64_t sizes[3];
      in.read(reinterpret_cast<char *>(sizes), sizeof(sizes));
      AssertThrow(in,
                  dealii::ExcMessage("Transient/Resume: checkpoint " + name +
                                     " is truncated."));
      if (rank == 0)
        {
          unsigned int k = 0;
          for (const char *f :
               {"energy.csv", "stiffness.csv", "pin_forces.csv"})
            {
              const std::string file = dir + "/" + f;
              AssertThrow(size_of(file) >= sizes[k],
                          dealii::ExcMessage(
                            "Transient/Resume: " + file +
                            " is shorter than at the checkpoint."));
              std::filesystem::resize_file(file, sizes[k++]);
            }
        }
      dealii::Utilities::MPI::sum(1, this->comm);
      return step;
    }



    template <int dim>
    void
    Transient<dim>::write_hdf5() const
    {
      // (The timer's sections synchronise over the ranks: enter on all.)
      dealii::TimerOutput::Scope scope(this->timer, "hdf5");
      if (dealii::Utilities::MPI::this_mpi_process(this->comm) != 0)
        return;
      const auto        &dir = this->prm.run.output_directory;
      const auto        &h   = history;
      const unsigned int n   = h.time.size();
      const unsigned int np =
        this->prm.scene.n_discs * this->prm.geometry.n_pins;
      const std::string tmp = dir + "/transient.h5.tmp";
      {
        dealii::HDF5::File file(tmp,
                                dealii::HDF5::File::FileAccessMode::create);
        file.set_attribute("scheme", this->prm.transient.scheme);
        file.set_attribute("time_step_s", this->prm.transient.time_step);
        file.set_attribute("crank_speed_deg_per_s",
                           this->prm.transient.crank_speed);
        file.set_attribute("number_of_pins", this->prm.geometry.n_pins);
        file.set_attribute("number_of_discs", this->prm.scene.n_discs);
        file.set_attribute(
          "pin_force_layout",
          std::string("pin_forces/*[step, disc * number_of_pins + pin] [N]"));
        const std::vector<std::pair<std::string, const std::vector<double> *>>
          series{{"time_s", &h.time},
                 {"crank_deg", &h.crank_deg},
                 {"torque_Nm", &h.torque},
                 {"rotation_rad", &h.rotation},
                 {"K_secant_Nm_per_rad", &h.k_secant},
                 {"kinetic_J", &h.kinetic},
                 {"elastic_J", &h.elastic},
                 {"external_work_J", &h.external_work},
                 {"dissipated_J", &h.dissipated},
                 {"balance_error_J", &h.balance},
                 {"max_penetration_um", &h.penetration},
                 {"active_set_iterations", &h.iterations},
                 {"angular_momentum_Nms", &h.angular_momentum}};
        for (const auto &[name, data] : series)
          if (n > 0)
            file.create_dataset<double>(name, {n}).write(*data);
        auto group = file.create_group("pin_forces");
        for (const auto &[name, data] :
             std::vector<std::pair<std::string, const std::vector<double> *>>{
               {"Fx_N", &h.fx}, {"Fy_N", &h.fy}, {"Fn_N", &h.fn}})
          if (n > 0)
            {
              dealii::FullMatrix<double> m(n, np);
              for (unsigned int i = 0; i < n; ++i)
                for (unsigned int k = 0; k < np; ++k)
                  m(i, k) = (*data)[i * np + k];
              group.create_dataset<double>(name, {n, np}).write(m);
            }
      }
      std::filesystem::rename(tmp, dir + "/transient.h5");
    }



    template class Transient<2>;
    template class Transient<3>;
  } // namespace dynamics
} // namespace cycloid

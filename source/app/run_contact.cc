#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>

#include <cycloid/app/run.h>
#include <cycloid/contact/quasi_static.h>
#include <cycloid/dynamics/transient.h>
#include <cycloid/postprocess/result_writer.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

namespace cycloid
{
  namespace app
  {
    namespace
    {
      /** Stamp a solved state with its step and crank angle and print a
       * one-line summary. */
      void
      report_state(const bool                             root,
                   const unsigned int                     step,
                   const double                           crank_deg,
                   postprocess::StiffnessRow             &row,
                   std::vector<postprocess::PinForceRow> &pins,
                   const std::string                     &prefix)
      {
        row.step      = step;
        row.crank_deg = crank_deg;
        for (auto &p : pins)
          {
            p.step      = step;
            p.crank_deg = crank_deg;
          }
        if (root)
          std::cout << prefix << "T " << row.torque_Nm << " N m, beta "
                    << row.rotation_rad << " rad, K_secant " << row.k_secant
                    << ", K_tangent " << row.k_tangent << " N m/rad ("
                    << row.k_tangent * postprocess::rad_per_arcmin
                    << " N m/arcmin), pins " << row.pins_in_contact
                    << ", active-set iterations " << row.iterations << ", dofs "
                    << row.dofs << ", " << row.wall_s << " s" << std::endl;
      }



      std::string
      scene_description(const parameters::AllParameters &prm)
      {
        std::ostringstream s;
        s << prm.scene.dimension << "D, " << prm.scene.n_discs << " disc(s), "
          << (prm.scene.pins == parameters::SceneParameters::PinModel::rigid ?
                "rigid" :
                "elastic")
          << " pins";
        return s.str();
      }



      template <int dim>
      void
      quasi_static(const parameters::AllParameters &prm, const MPI_Comm comm)
      {
        const bool   root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
        const double psi =
          prm.loading.crank_angle_deg * dealii::numbers::PI / 180.;
        if (root)
          std::cout << "cycloid-contact: quasi-static FE contact, "
                    << scene_description(prm) << ", crank angle "
                    << prm.loading.crank_angle_deg << " deg, "
                    << prm.loading.load_values().size()
                    << (prm.loading.rotation_control ? " rotation(s)" :
                                                       " torque(s)")
                    << std::endl;
        // The scene is checked while it is built: no result files for a
        // scene that cannot be solved.
        contact::QuasiStatic<dim> solver(prm, psi, comm);
        postprocess::ResultWriter writer(prm.run.output_directory, root);
        std::vector<std::pair<double, std::string>> records;
        const std::vector<double> loads = prm.loading.load_values();
        for (unsigned int step = 0; step < loads.size(); ++step)
          {
            postprocess::StiffnessRow             row;
            std::vector<postprocess::PinForceRow> pins;
            solver.solve(loads[step], row, pins);
            report_state(root,
                         step,
                         prm.loading.crank_angle_deg,
                         row,
                         pins,
                         "  state " + std::to_string(step + 1) + "/" +
                           std::to_string(loads.size()) + ": ");
            writer.write(row, pins);
            if (prm.run.write_solution)
              solver.output_results(step, records);
          }
        solver.print_timing();
      }



      template <int dim>
      void
      phase_sweep(const parameters::AllParameters &prm, const MPI_Comm comm)
      {
        const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
        const geometry::CycloidGeometry geo(prm.geometry);
        const std::vector<double>       angles =
          prm.loading.crank_angles(geo.mesh_period());
        const std::vector<double> torques  = prm.loading.load_values();
        const double              to_deg   = 180. / dealii::numbers::PI;
        const unsigned int        n_states = angles.size() * torques.size();
        if (root)
          std::cout << "cycloid-contact: phase sweep, FE contact, "
                    << scene_description(prm) << ", " << angles.size()
                    << " crank angles over " << geo.mesh_period() * to_deg
                    << " deg x " << torques.size() << " torque(s)" << std::endl;
        std::unique_ptr<postprocess::ResultWriter>  writer;
        std::vector<std::pair<double, std::string>> records;
        // Per torque: the last phase's active set (warm start) and the
        // stiffness over the phases.
        std::vector<std::vector<std::pair<contact::SlaveNode<dim>, bool>>>
                                         snapshots(torques.size());
        std::vector<std::vector<double>> k_tangent(torques.size()),
          k_secant(torques.size());
        const auto   start = std::chrono::steady_clock::now();
        unsigned int step  = 0;
        for (unsigned int k = 0; k < angles.size(); ++k)
          {
            contact::QuasiStatic<dim> solver(prm, angles[k], comm);
            if (!writer)
              writer = std::make_unique<postprocess::ResultWriter>(
                prm.run.output_directory, root);
            for (unsigned int t = 0; t < torques.size(); ++t, ++step)
              {
                solver.warm_start(snapshots[t]);
                postprocess::StiffnessRow             row;
                std::vector<postprocess::PinForceRow> pins;
                solver.solve(torques[t], row, pins);
                snapshots[t] = solver.active_set_snapshot();
                const double elapsed =
                  std::chrono::duration<double>(
                    std::chrono::steady_clock::now() - start)
                    .count();
                std::ostringstream prefix;
                prefix << "  phase " << k + 1 << "/" << angles.size()
                       << " (crank " << std::setprecision(5)
                       << angles[k] * to_deg << " deg), elapsed "
                       << std::setprecision(3) << elapsed << " s, remaining ~"
                       << elapsed * (n_states - step - 1) / (step + 1)
                       << " s: " << std::setprecision(6);
                report_state(
                  root, step, angles[k] * to_deg, row, pins, prefix.str());
                writer->write(row, pins);
                if (prm.run.write_solution)
                  solver.output_results(step, records);
                k_tangent[t].push_back(row.k_tangent);
                k_secant[t].push_back(row.k_secant);
              }
          }

        // Fluctuation over the period, and the closure of the period (the
        // first and last phase are one mesh period apart).
        if (!root)
          return;
        std::ofstream out(prm.run.output_directory + "/fluctuation.csv");
        out << (prm.loading.rotation_control ? "rotation_rad" : "torque_Nm")
            << ",n_phases,K_tangent_mean_Nm_per_rad,"
               "K_tangent_min_Nm_per_rad,K_tangent_max_Nm_per_rad,"
               "K_tangent_fluctuation,K_secant_mean_Nm_per_rad,"
               "K_secant_fluctuation,K_tangent_period_closure\n"
            << std::setprecision(12);
        for (unsigned int t = 0; t < torques.size(); ++t)
          {
            const auto stats = [](const std::vector<double> &v) {
              const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
              double mean         = 0;
              for (const double x : v)
                mean += x;
              mean /= v.size();
              return std::array<double, 4>{
                {mean, *lo, *hi, (*hi - *lo) / mean}};
            };
            const auto   kt = stats(k_tangent[t]);
            const auto   ks = stats(k_secant[t]);
            const double closure =
              k_tangent[t].back() / k_tangent[t].front() - 1;
            out << torques[t] << ',' << angles.size() << ',' << kt[0] << ','
                << kt[1] << ',' << kt[2] << ',' << kt[3] << ',' << ks[0] << ','
                << ks[3] << ',' << closure << '\n';
            std::cout << "  torque " << torques[t]
                      << " N m: K_tangent over the period mean " << kt[0]
                      << ", min " << kt[1] << ", max " << kt[2]
                      << " N m/rad; fluctuation (max-min)/mean " << kt[3]
                      << "; first vs last phase " << closure << std::endl;
          }
        std::cout << "  results in " << prm.run.output_directory
                  << "/stiffness.csv, pin_forces.csv, fluctuation.csv"
                  << std::endl;
      }
    } // namespace



    void
    run_quasi_static(const parameters::AllParameters &prm, const MPI_Comm comm)
    {
      if (prm.scene.dimension == 2)
        quasi_static<2>(prm, comm);
      else
        quasi_static<3>(prm, comm);
    }



    void
    run_phase_sweep(const parameters::AllParameters &prm, const MPI_Comm comm)
    {
      if (prm.scene.dimension == 2)
        phase_sweep<2>(prm, comm);
      else
        phase_sweep<3>(prm, comm);
    }
    namespace
    {
      /** Create the output directory on rank 0 (after the scene was built:
       * a scene that cannot be solved leaves no files). */
      void
      make_output_directory(const parameters::AllParameters &prm,
                            const MPI_Comm                   comm)
      {
        std::error_code ec;
        if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
          std::filesystem::create_directories(prm.run.output_directory, ec);
        const bool failed = dealii::Utilities::MPI::max(ec ? 1 : 0, comm);
        AssertThrow(!failed,
                    dealii::ExcMessage("Output directory '" +
                                       prm.run.output_directory +
                                       "' cannot be created."));
      }
    } // namespace



    void
    run_transient(const parameters::AllParameters &prm, const MPI_Comm comm)
    {
      const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      if (root)
        std::cout << "cycloid-contact: transient FE contact, "
                  << scene_description(prm) << ", from crank angle "
                  << prm.loading.crank_angle_deg << " deg" << std::endl;
      if (prm.scene.dimension == 2)
        {
          dynamics::Transient<2> solver(prm, comm);
          make_output_directory(prm, comm);
          solver.run();
        }
      else
        {
          dynamics::Transient<3> solver(prm, comm);
          make_output_directory(prm, comm);
          solver.run();
        }
    }
  } // namespace app
} // namespace cycloid

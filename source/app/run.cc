#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>

#include <cycloid/app/ignored_entries.h>
#include <cycloid/app/run.h>
#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/runs/analytic_run.h>
#include <cycloid/runs/mesh_run.h>
#include <cycloid/runs/phase_sweep.h>
#include <cycloid/runs/profile_run.h>
#include <cycloid/runs/quasi_static.h>
#include <cycloid/runs/reduced_run.h>
#include <cycloid/runs/tolerance_run.h>
#include <cycloid/runs/transient.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace cycloid
{
  namespace app
  {
    namespace
    {
      /** The FE scene's settings. */
      stage::StageSettings
      stage_settings(const AllParameters &prm)
      {
        stage::StageSettings s;
        s.geometry         = prm.geometry;
        s.material         = prm.material;
        s.scene            = prm.scene;
        s.mesh             = prm.mesh;
        s.contact          = prm.contact;
        s.analytic         = prm.analytic;
        s.bearings         = prm.bearings;
        s.rotation_control = prm.loading.rotation_control;
        s.output_directory = prm.run.output_directory;
        return s;
      }

      /** An FE run's settings. */
      runs::FeRunSettings
      fe_run_settings(const AllParameters &prm)
      {
        return {stage_settings(prm), prm.loading, prm.run.write_solution};
      }

      /** @p s without the error estimate (runs that keep one mesh: the
       * transient, whose mesh is not refined during the run, and the
       * reduced model's coarse scene). */
      template <typename Settings>
      Settings
      without_estimate(Settings s)
      {
        s.mesh.error.mode            = mesh::ErrorControl::Mode::off;
        s.mesh.error.target_accuracy = 0;
        return s;
      }

      /** Make the output directory and write `parameters.prm` and
       * `parameters.json` into it. */
      void
      prepare_output_directory(const AllParameters &prm, const MPI_Comm comm)
      {
        make_output_directory(prm.run.output_directory, comm);
        write_parameter_file(prm.run.output_directory,
                             "parameters.prm",
                             prm.parameter_file,
                             comm);
        write_parameter_file(prm.run.output_directory,
                             "parameters.json",
                             prm.parameter_json,
                             comm);
      }



      /** Build the run (it checks its scene: a scene that cannot be solved
       * leaves no files), make the output directory, run. */
      template <typename Run, typename Settings>
      void
      build_and_run(const Settings      &settings,
                    const AllParameters &prm,
                    const MPI_Comm       comm)
      {
        Run run(settings, comm);
        prepare_output_directory(prm, comm);
        run.run();
      }

      /** The FE run modes of dimension @p dim. */
      template <int dim>
      void
      run_fe(const AllParameters &prm, const MPI_Comm comm)
      {
        using Mode = parameters::RunParameters::Mode;
        switch (prm.run.mode)
          {
              case Mode::mesh: {
                // The directory first: the mesher may write stage.msh.
                prepare_output_directory(prm, comm);
                runs::MeshRun<dim> run(
                  {prm.mesh_settings(),
                   runs::mesh_request(fe_run_settings(prm),
                                      prm.loading.crank_angle()),
                   prm.run.output_directory},
                  comm);
                run.run();
                return;
              }
            case Mode::quasi_static:
              build_and_run<runs::QuasiStaticRun<dim>>(fe_run_settings(prm),
                                                       prm,
                                                       comm);
              return;
            case Mode::phase_sweep:
              build_and_run<runs::PhaseSweepRun<dim>>(fe_run_settings(prm),
                                                      prm,
                                                      comm);
              return;
            case Mode::transient:
              build_and_run<runs::TransientRun<dim>>(
                typename runs::TransientRun<dim>::Settings{
                  {without_estimate(stage_settings(prm)),
                   prm.loading,
                   prm.run.write_solution},
                  prm.transient},
                prm,
                comm);
              return;
            case Mode::reduced:
              build_and_run<runs::ReducedRun<dim>>(
                typename runs::ReducedRun<dim>::Settings{
                  {without_estimate(stage_settings(prm)), prm.reduced},
                  prm.loading},
                prm,
                comm);
              return;
            case Mode::tolerance:
              build_and_run<runs::ToleranceRun<dim>>(
                typename runs::ToleranceRun<dim>::Settings{
                  {without_estimate(stage_settings(prm)), prm.reduced},
                  prm.loading,
                  prm.tolerance},
                prm,
                comm);
              return;
            default:
              AssertThrow(false, dealii::ExcInternalError());
          }
      }
    } // namespace



    void
    make_output_directory(const std::string &directory, const MPI_Comm comm)
    {
      // Rank 0 makes it; every rank learns the system's reason, so that
      // the error names it on every rank (see app/error_report.h).
      std::string reason;
      if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        {
          std::error_code ec;
          std::filesystem::create_directories(directory, ec);
          if (ec)
            reason = ec.message();
        }
      reason = dealii::Utilities::MPI::broadcast(comm, reason, 0);
      AssertThrow(reason.empty(),
                  dealii::ExcMessage("Output directory '" + directory +
                                     "' cannot be created: " + reason + "."));
    }



    void
    write_parameter_file(const std::string &directory,
                         const std::string &name,
                         const std::string &text,
                         const MPI_Comm     comm)
    {
      if (text.empty())
        return;
      // Rank 0 writes; the others learn whether it could, so that a failure
      // is an error on every rank (see app/error_report.h).
      bool written = true;
      if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        {
          std::ofstream out(directory + "/" + name);
          out << text;
          out.close();
          written = static_cast<bool>(out);
        }
      const bool failed = dealii::Utilities::MPI::max(written ? 0 : 1, comm);
      AssertThrow(!failed,
                  dealii::ExcMessage("cannot write to Output directory '" +
                                     directory + "' (" + name + ")."));
    }



    std::string
    stage_line(const geometry::GeometryParameters &g)
    {
      try
        {
          const geometry::CycloidGeometry geo(g);
          // The rest clearance along the normals over one mesh period
          // (the modified profile's; 0 for the conjugate one), both discs.
          double             lo = std::numeric_limits<double>::max(), hi = -lo;
          const unsigned int n_phases = 10;
          for (unsigned int k = 0; k < n_phases; ++k)
            for (unsigned int d = 0; d < 2; ++d)
              for (const auto &c :
                   geo.pin_contacts(d, geo.mesh_period() * k / n_phases))
                {
                  lo = std::min(lo, c.clearance);
                  hi = std::max(hi, c.clearance);
                }
          std::ostringstream s;
          s << std::setprecision(6) << "stage: zp = " << g.n_pins
            << ", rp = " << geo.pin_circle_radius()
            << " mm, K1 = " << g.shortening_coefficient
            << ", e = " << g.eccentricity << " mm, rrp = " << g.pin_radius
            << " mm, b = " << g.tooth_width << " mm; rest clearance "
            << std::setprecision(3) << std::max(0., lo * 1e3) << " to "
            << std::max(0., hi * 1e3)
            << " um (Delta rp = " << g.delta_pin_circle_radius * 1e3
            << " um, Delta rrp = " << g.delta_pin_radius * 1e3 << " um)";
          return s.str();
        }
      catch (const dealii::ExceptionBase &)
        {
          // The run's own check reports the geometry error.
          return "";
        }
    }



    void
    announce_parameters(const AllParameters &prm, const MPI_Comm comm)
    {
      if (dealii::Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      for (const std::string &note : prm.notes)
        std::cout << note << std::endl;
      const std::string stage = stage_line(prm.geometry);
      if (!stage.empty())
        std::cout << stage << std::endl;
      std::map<std::string, std::string> changed = prm.set_in_file;
      for (const std::string &name : prm.set_to_default)
        changed.erase(name);
      for (const std::string &warning :
           ignored_entry_warnings({prm.run.mode,
                                   prm.scene.dimension,
                                   prm.mesh.refine_loaded_side_only,
                                   prm.bearings.needle()},
                                  changed))
        std::cerr << warning << std::endl;
    }



    void
    run(const AllParameters &prm, const MPI_Comm comm)
    {
      announce_parameters(prm, comm);
      if (prm.run.mode == parameters::RunParameters::Mode::analytic)
        build_and_run<runs::AnalyticRun>(
          runs::AnalyticRun::Settings{prm.model_settings(),
                                      prm.loading,
                                      prm.run.output_directory},
          prm,
          comm);
      else if (prm.run.mode == parameters::RunParameters::Mode::profile)
        // The exact curve only: no mesh, no FE.
        build_and_run<runs::ProfileRun>(
          runs::ProfileRun::Settings{prm.geometry,
                                     prm.profile,
                                     prm.run.output_directory},
          prm,
          comm);
      else if (prm.scene.dimension == 2)
        run_fe<2>(prm, comm);
      else
        run_fe<3>(prm, comm);
    }
  } // namespace app
} // namespace cycloid

#include <deal.II/base/mpi.h>

#include <cycloid/profile/csv_writer.h>
#include <cycloid/profile/dxf_writer.h>
#include <cycloid/profile/outline.h>
#include <cycloid/profile/step_writer.h>
#include <cycloid/runs/profile_run.h>

#include <chrono>
#include <filesystem>
#include <iostream>

namespace cycloid
{
  namespace runs
  {
    namespace
    {
      /** Size of @p file in kB, for the console. */
      double
      kilobytes(const std::string &file)
      {
        return std::filesystem::file_size(file) / 1024.;
      }
    } // namespace



    ProfileRun::ProfileRun(const Settings &settings, const MPI_Comm comm)
      : settings(settings)
      , comm(comm)
      , geometry(settings.geometry)
    {}



    void
    ProfileRun::run()
    {
      if (dealii::Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      const auto   start = std::chrono::steady_clock::now();
      const double tol   = settings.profile.chord_tolerance;
      const auto  &geo   = settings.geometry;
      std::cout << "cycloid-contact: profile of one disc, zc = " << geo.n_teeth
                << ", Delta rp = " << geo.delta_pin_circle_radius
                << " mm, Delta rrp = " << geo.delta_pin_radius
                << " mm, chord tolerance " << tol * 1e3 << " um" << std::endl;

      const profile::DiscOutline outline =
        profile::sample_outline(geometry, tol);
      const std::string dir = settings.output_directory + "/";
      profile::write_csv(outline, dir + "profile.csv");
      profile::write_dxf(outline, dir + "profile.dxf");
      const profile::StepSummary step =
        profile::write_step(geometry, outline, dir + "profile.step");

      const unsigned int n = outline.vertices.size();
      std::cout << "  " << dir << "profile.csv: " << n
                << " vertices, counter-clockwise, the first repeated at the "
                   "end ("
                << kilobytes(dir + "profile.csv") << " kB)\n"
                << "  " << dir << "profile.dxf: closed POLYLINE of " << n
                << " vertices on layer PROFILE, " << outline.holes.size()
                << " CIRCLEs (bore + " << outline.holes.size() - 1
                << " crank holes) on layer HOLES ("
                << kilobytes(dir + "profile.dxf") << " kB)\n"
                << "  " << dir
                << "profile.step: planar face, periodic cubic B-spline "
                   "through "
                << step.n_spline_points << " profile points, "
                << outline.holes.size() << " circular holes, max deviation "
                << step.max_deviation * 1e3 << " um ("
                << kilobytes(dir + "profile.step") << " kB)\n"
                << "  max chord deviation " << outline.max_chord_deviation * 1e3
                << " um (tolerance " << tol * 1e3 << " um), "
                << std::chrono::duration<double>(
                     std::chrono::steady_clock::now() - start)
                     .count()
                << " s" << std::endl;
    }
  } // namespace runs
} // namespace cycloid

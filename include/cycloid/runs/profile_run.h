#ifndef cycloid_runs_profile_run_h
#define cycloid_runs_profile_run_h

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/profile/profile_parameters.h>

#include <string>

#include <mpi.h>

namespace cycloid
{
  namespace runs
  {
    /**
     * @brief `Run = profile`: the modified profile of one disc in its own
     * frame, with the bore and crank holes, for CAD and manufacturing:
     * `profile.csv`, `profile.dxf` and `profile.step` at
     * `Profile/Chord tolerance`. No mesh and no FE; rank 0 writes (other
     * ranks check the geometry alike, then return).
     */
    class ProfileRun
    {
    public:
      /** What the run reads from the parameter file. */
      struct Settings
      {
        geometry::GeometryParameters geometry;   ///< The disc.
        profile::ProfileParameters   profile;    ///< The chord tolerance.
        std::string output_directory = "output"; ///< Where the files go.
      };

      /** Build the geometry (checking it). */
      ProfileRun(const Settings &settings, const MPI_Comm comm);

      /** Sample the profile and write the three files. */
      void
      run();

    private:
      const Settings                  settings;
      const MPI_Comm                  comm;
      const geometry::CycloidGeometry geometry;
    };
  } // namespace runs
} // namespace cycloid

#endif

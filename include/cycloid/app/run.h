#ifndef cycloid_app_run_h
#define cycloid_app_run_h

#include <cycloid/app/all_parameters.h>

#include <mpi.h>

namespace cycloid
{
  /**
   * The application layer: the only code that sees the whole parameter
   * set. It turns it into each run's typed settings, builds the run
   * selected by `Run` (which checks the scene), makes the output directory
   * once, and runs it.
   */
  namespace app
  {
    /** Run the mode selected by `Run` in @p parameters on @p comm, after
     * announce_parameters(). */
    void
    run(const AllParameters &parameters, const MPI_Comm comm);

    /** On rank 0 of @p comm: print what @p parameters resolved on their
     * own (AllParameters::notes, stdout), the stage line (stage_line()),
     * and a warning line for every entry the file sets that the run mode
     * ignores (stderr, ignored_entry_warnings()). */
    void
    announce_parameters(const AllParameters &parameters, const MPI_Comm comm);

    /** "stage: zp = 40, rp = 130.37 mm, K1 = 0.675, e = 2.2 mm, rrp = 3 mm,
     * b = 16 mm; rest clearance 0 to 0 um (Delta rp = 0 um, Delta rrp =
     * 0 um)": the inputs a designer thinks in, and the rest clearance
     * along the contact normals over one mesh period (both discs), so the
     * modification's effect is read before any state; "" if @p geometry
     * is not a valid stage (the run's own check then says why). */
    std::string
    stage_line(const geometry::GeometryParameters &geometry);

    /** Create @p directory on rank 0 (collective; throws naming it if it
     * cannot be made). */
    void
    make_output_directory(const std::string &directory, const MPI_Comm comm);

    /** Write @p text (the run's parameters, AllParameters::parameter_file
     * or parameter_json) as @p name (`parameters.prm`, `parameters.json`)
     * into @p directory on rank 0; collective (every rank throws if it
     * cannot be written). Nothing if @p text is empty. */
    void
    write_parameter_file(const std::string &directory,
                         const std::string &name,
                         const std::string &text,
                         const MPI_Comm     comm);
  } // namespace app
} // namespace cycloid

#endif

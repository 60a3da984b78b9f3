#ifndef cycloid_app_error_report_h
#define cycloid_app_error_report_h

#include <exception>
#include <string>

#include <mpi.h>

namespace cycloid
{
  namespace app
  {
    /**
     * The message of @p error for the user, trimmed: for a deal.II
     * exception its own text without the stack banner of what() ("An error
     * occurred in line ..."), else what().
     */
    std::string
    error_message(const std::exception_ptr &error);

    /**
     * Report @p error, which ended the run on this rank, once on @p comm,
     * and return the exit status (1).
     *
     * Most errors happen on every rank: the input is the same everywhere
     * and the solvers' decisions are collective. Such an error is printed
     * by rank 0 only, as one "Error: ..." line. But an error can also
     * happen on one rank alone (rank 0 cannot write a file, memory runs
     * out), while the others go on into the next collective operation and
     * would wait for this rank forever. So every failed rank enters a
     * non-blocking barrier (blocking collectives elsewhere do not match
     * it) and polls it for @p timeout_seconds: if every rank arrives, the
     * error was collective; if not, this rank prints its message prefixed
     * by its rank and stops all ranks with MPI_Abort (exit status 1).
     */
    int
    report_error(const std::exception_ptr &error,
                 const MPI_Comm            comm,
                 const double              timeout_seconds = 5.);
  } // namespace app
} // namespace cycloid

#endif

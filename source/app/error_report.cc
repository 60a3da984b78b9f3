#include <deal.II/base/exceptions.h>

#include <deal.II/base/utilities.h>

#include <cycloid/app/error_report.h>

#include <chrono>
#include <iostream>
#include <sstream>
#include <thread>

namespace cycloid
{
  namespace app
  {
    namespace
    {
      /**
       * Whether every rank of @p comm reaches this call within
       * @p timeout_seconds (every rank then reports an error).
       *
       * The ranks of a collective error arrive together: they unwind the
       * same stack from the same collective decision, so a few seconds
       * cover any skew. A rank that does not arrive is either busy or
       * blocked in a blocking collective, which an MPI_Ibarrier never
       * matches (MPI-3: non-blocking and blocking collectives do not
       * match each other). What would defeat the timeout is a blocking
       * collective on the failed rank between the throw and this call, in
       * a destructor during the unwinding: the stage's timers used to
       * make one, so they run on MPI_COMM_SELF (stage_scene.cc); the
       * other destructors of the runs only free memory.
       */
      bool
      every_rank_failed(const MPI_Comm comm, const double timeout_seconds)
      {
        MPI_Request request;
        if (MPI_Ibarrier(comm, &request) != MPI_SUCCESS)
          return false;
        const auto deadline = std::chrono::steady_clock::now() +
                              std::chrono::duration<double>(timeout_seconds);
        int done = 0;
        while (true)
          {
            if (MPI_Test(&request, &done, MPI_STATUS_IGNORE) != MPI_SUCCESS)
              return false;
            if (done != 0)
              return true;
            if (std::chrono::steady_clock::now() > deadline)
              return false;
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
          }
      }



      /** Whether MPI can be used (it is initialised and not finalised). */
      bool
      mpi_active()
      {
        int initialized = 0, finalized = 0;
        MPI_Initialized(&initialized);
        MPI_Finalized(&finalized);
        return initialized != 0 && finalized == 0;
      }
    } // namespace



    std::string
    error_message(const std::exception_ptr &error)
    {
      std::ostringstream s;
      try
        {
          std::rethrow_exception(error);
        }
      catch (const dealii::ExceptionBase &e)
        {
          e.print_info(s);
        }
      catch (const std::exception &e)
        {
          s << e.what();
        }
      catch (...)
        {
          s << "unknown exception.";
        }
      return dealii::Utilities::trim(s.str());
    }



    int
    report_error(const std::exception_ptr &error,
                 const MPI_Comm            comm,
                 const double              timeout_seconds)
    {
      // The progress lines first, then the error after them.
      std::cout.flush();
      const std::string message = error_message(error);
      if (!mpi_active())
        {
          std::cerr << "Error: " + message + "\n" << std::flush;
          return 1;
        }
      int rank = 0;
      MPI_Comm_rank(comm, &rank);
      if (every_rank_failed(comm, timeout_seconds))
        {
          // One string in one write: nothing can come between its parts.
          if (rank == 0)
            std::cerr << "Error: " + message + "\n" << std::flush;
          return 1;
        }
      std::cerr << "[rank " + std::to_string(rank) + "] Error: " + message +
                     "\n(This error happened on rank " + std::to_string(rank) +
                     " only; stopping all ranks.)\n"
                << std::flush;
      MPI_Abort(comm, 1);
      return 1;
    }
  } // namespace app
} // namespace cycloid

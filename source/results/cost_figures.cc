#include <deal.II/base/utilities.h>

#include <cycloid/results/cost_figures.h>

namespace cycloid
{
  namespace results
  {
    double
    seconds_since(const Clock::time_point start)
    {
      return std::chrono::duration<double>(Clock::now() - start).count();
    }



    double
    peak_memory_MB(const MPI_Comm comm)
    {
      dealii::Utilities::System::MemoryStats stats;
      dealii::Utilities::System::get_memory_stats(stats);
      return dealii::Utilities::MPI::sum(static_cast<double>(stats.VmHWM),
                                         comm) /
             1024.;
    }
  } // namespace results
} // namespace cycloid

#ifndef cycloid_results_cost_figures_h
#define cycloid_results_cost_figures_h

#include <deal.II/base/mpi.h>

#include <chrono>

namespace cycloid
{
  namespace results
  {
    /**
     * The two cost figures every state carries (StageState::wall_s and
     * StageState::peak_memory_MB), measured in one place with one meaning
     * each, for every model.
     */
    /** @{ */

    /** The clock of StageState::wall_s. */
    using Clock = std::chrono::steady_clock;

    /** Seconds of wall time since @p start. */
    double
    seconds_since(const Clock::time_point start);

    /** Peak resident memory (VmHWM) summed over the ranks of @p comm [MB]
     * (collective). A model that computes on one rank only passes
     * MPI_COMM_SELF. */
    double
    peak_memory_MB(const MPI_Comm comm);

    /** @} */
  } // namespace results
} // namespace cycloid

#endif

#ifndef cycloid_dynamics_checkpoint_h
#define cycloid_dynamics_checkpoint_h

#include <fstream>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>

#include <mpi.h>

namespace cycloid
{
  namespace dynamics
  {
    /**
     * @brief Checkpoint files of a transient run: one binary file per MPI
     * rank (`checkpoint.rank-R.bin` in the output directory) holding the
     * step, the time and whatever the run's pieces save into it (scheme
     * state, energy account, time series, CSV sizes). A new checkpoint is
     * written beside the old one and replaces it only once every rank has
     * written its file, so an interrupted write leaves the previous
     * checkpoint intact. A restart needs the same number of ranks.
     */
    class Checkpoint
    {
    public:
      /** Checkpoints in @p directory of the ranks of @p comm. */
      Checkpoint(const std::string &directory, const MPI_Comm comm);

      /** Write the checkpoint of step @p step at @p time [s]; @p save
       * writes the pieces' state into the stream (collective). */
      void
      write(const unsigned int                         step,
            const double                               time,
            const std::function<void(std::ostream &)> &save) const;

      /** Open this rank's checkpoint, check that it was written on as many
       * ranks, and read its step and time; the stream is left at the
       * pieces' state. Throws with the cure if there is none. */
      std::unique_ptr<std::ifstream>
      open(unsigned int &step, double &time) const;

      /** Throw if @p in failed (a truncated checkpoint). */
      void
      check(const std::istream &in) const;

    private:
      /** This rank's file. */
      std::string
      file() const;

      const std::string  directory;
      const MPI_Comm     comm;
      const unsigned int rank;
      const unsigned int n_ranks;
    };
  } // namespace dynamics
} // namespace cycloid

#endif

#ifndef cycloid_dynamics_checkpoint_h
#define cycloid_dynamics_checkpoint_h

#include <deal.II/base/index_set.h>

#include <deal.II/lac/trilinos_vector.h>

#include <cstdint>
#include <fstream>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include <mpi.h>

namespace cycloid
{
  namespace dynamics
  {
    /**
     * @brief One pass over the fields of a checkpoint, writing them or
     * reading them back.
     *
     * Each piece of a run lists its fields once, in one function that
     * takes an archive (`void checkpoint(CheckpointArchive &)`); the same
     * list writes the checkpoint and restores it, so the two cannot drift
     * apart (the role of `serialize(Archive &)` in deal.II and boost).
     * Binary, native byte order: doubles as 8 bytes, counts and indices as
     * unsigned 64-bit integers.
     */
    class CheckpointArchive
    {
    public:
      /** An archive that writes to @p out. */
      explicit CheckpointArchive(std::ostream &out)
        : out(&out)
      {}

      /** An archive that reads from @p in. */
      explicit CheckpointArchive(std::istream &in)
        : in(&in)
      {}

      /** True if this archive restores (reads) the fields. */
      bool
      loading() const
      {
        return in != nullptr;
      }

      /** True if a reading archive has nothing left (an older checkpoint
       * that ends before a field added since); false when writing. */
      bool
      at_end() const;

      /** Throw with @p what if a reading archive failed (a truncated file). */
      void
      check(const std::string &what) const;

      /** A double. */
      void
      value(double &x)
      {
        raw(&x, sizeof(double));
      }

      /** A count or an index, stored as an unsigned 64-bit integer. */
      template <typename Integer>
      void
      count(Integer &n)
      {
        static_assert(std::is_integral_v<Integer>);
        std::uint64_t stored = n;
        raw(&stored, sizeof(stored));
        n = static_cast<Integer>(stored);
      }

      /** The size of @p v (resized when reading), then each element through
       * @p each(element). */
      template <typename T, typename Each>
      void
      sequence(std::vector<T> &v, const Each &each)
      {
        std::size_t n = v.size();
        count(n);
        v.resize(n);
        for (T &x : v)
          each(x);
      }

      /** A vector of plain numbers (its size, then its bytes). */
      template <typename T>
      void
      array(std::vector<T> &v)
      {
        static_assert(std::is_arithmetic_v<T>);
        std::size_t n = v.size();
        count(n);
        v.resize(n);
        raw(v.data(), n * sizeof(T));
      }

      /** The number of DoFs this rank owns; a restore checks it against
       * @p owned (a different mesh or partition is an error). */
      void
      owned_count(const dealii::IndexSet &owned);

      /**
       * The entries of @p x this rank owns (@p owned), without their number
       * (owned_count() states it once for the vectors that follow). Reading
       * makes @p x a ghosted vector over @p owned and @p relevant.
       */
      void
      owned_entries(dealii::TrilinosWrappers::MPI::Vector &x,
                    const dealii::IndexSet                &owned,
                    const dealii::IndexSet                &relevant,
                    const MPI_Comm                         comm);

    private:
      /** Write or read @p size bytes at @p data. */
      void
      raw(void *data, const std::size_t size);

      std::ostream *out = nullptr;
      std::istream *in  = nullptr;
    };



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

#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>

#include <cycloid/dynamics/checkpoint.h>

#include <cstdint>
#include <filesystem>

namespace cycloid
{
  namespace dynamics
  {
    bool
    CheckpointArchive::at_end() const
    {
      return in != nullptr && in->peek() == std::char_traits<char>::eof();
    }



    void
    CheckpointArchive::check(const std::string &what) const
    {
      AssertThrow(in == nullptr || *in, dealii::ExcMessage(what));
    }



    void
    CheckpointArchive::raw(void *data, const std::size_t size)
    {
      if (in != nullptr)
        in->read(static_cast<char *>(data), size);
      else
        out->write(static_cast<const char *>(data), size);
    }



    void
    CheckpointArchive::owned_count(const dealii::IndexSet &owned)
    {
      std::size_t n = owned.n_elements();
      count(n);
      check("checkpoint: the file is truncated.");
      AssertThrow(n == owned.n_elements(),
                  dealii::ExcMessage(
                    "checkpoint: the mesh or the partition differs from the "
                    "run that wrote it (restart with the same prm and the "
                    "same number of MPI ranks)."));
    }



    void
    CheckpointArchive::owned_entries(dealii::TrilinosWrappers::MPI::Vector &x,
                                     const dealii::IndexSet &owned,
                                     const dealii::IndexSet &relevant,
                                     const MPI_Comm          comm)
    {
      if (!loading())
        {
          for (const auto i : owned)
            {
              double v = x[i];
              value(v);
            }
          return;
        }
      dealii::TrilinosWrappers::MPI::Vector o(owned, comm);
      for (const auto i : owned)
        {
          double v = 0;
          value(v);
          o[i] = v;
        }
      o.compress(dealii::VectorOperation::insert);
      x.reinit(owned, relevant, comm);
      x = o;
    }



    Checkpoint::Checkpoint(const std::string &directory, const MPI_Comm comm)
      : directory(directory)
      , comm(comm)
      , rank(dealii::Utilities::MPI::this_mpi_process(comm))
      , n_ranks(dealii::Utilities::MPI::n_mpi_processes(comm))
    {}



    std::string
    Checkpoint::file() const
    {
      return directory + "/checkpoint.rank-" + std::to_string(rank) + ".bin";
    }



    void
    Checkpoint::write(const unsigned int                         step,
                      const double                               time,
                      const std::function<void(std::ostream &)> &save) const
    {
      const std::string name = file();
      {
        std::ofstream       out(name + ".tmp", std::ios::binary);
        const std::uint64_t header[3] = {step, n_ranks, rank};
        out.write(reinterpret_cast<const char *>(header), sizeof(header));
        out.write(reinterpret_cast<const char *>(&time), sizeof(double));
        save(out);
        AssertThrow(out,
                    dealii::ExcMessage("checkpoint: cannot write " + name));
      }
      // All ranks done before any file replaces the previous checkpoint.
      dealii::Utilities::MPI::sum(1, comm);
      std::filesystem::rename(name + ".tmp", name);
    }



    std::unique_ptr<std::ifstream>
    Checkpoint::open(unsigned int &step, double &time) const
    {
      const std::string name = file();
      auto in = std::make_unique<std::ifstream>(name, std::ios::binary);
      AssertThrow(*in,
                  dealii::ExcMessage(
                    "Transient/Resume: no checkpoint " + name +
                    " (set Transient/Checkpoint interval in the run to "
                    "resume, and the same Output directory)."));
      std::uint64_t header[3];
      in->read(reinterpret_cast<char *>(header), sizeof(header));
      in->read(reinterpret_cast<char *>(&time), sizeof(double));
      AssertThrow(*in && header[1] == n_ranks && header[2] == rank,
                  dealii::ExcMessage(
                    "Transient/Resume: the checkpoint was written by " +
                    std::to_string(header[1]) +
                    " MPI rank(s); resume on the same number of ranks."));
      step = header[0];
      return in;
    }



    void
    Checkpoint::check(const std::istream &in) const
    {
      AssertThrow(in,
                  dealii::ExcMessage("Transient/Resume: checkpoint " + file() +
                                     " is truncated."));
    }
  } // namespace dynamics
} // namespace cycloid

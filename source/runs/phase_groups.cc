#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>

#include <cycloid/results/state_buffer.h>
#include <cycloid/runs/phase_groups.h>

#include <iterator>
#include <string>
#include <utility>

namespace cycloid
{
  namespace runs
  {
    namespace
    {
      /** Message tags of the collector's communicator. */
      constexpr int state_tag = 1, busy_tag = 2;
    } // namespace



    PhaseGroups::PhaseGroups(const MPI_Comm     world,
                             const unsigned int ranks_per_group,
                             const unsigned int n_phases)
      : n_phases(n_phases)
    {
      const unsigned int ranks = dealii::Utilities::MPI::n_mpi_processes(world);
      const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(world);
      size                    = ranks_per_group == 0 ? ranks : ranks_per_group;
      const std::string entry =
        "Loading/Ranks per phase group = " + std::to_string(ranks_per_group);
      AssertThrow(ranks % size == 0,
                  dealii::ExcMessage(
                    entry + " does not divide the " + std::to_string(ranks) +
                    " MPI rank(s): the number of ranks must be a multiple of "
                    "the group size (0 puts all ranks in one group)."));
      n = ranks / size;
      AssertThrow(n <= n_phases,
                  dealii::ExcMessage(
                    entry + " makes " + std::to_string(n) + " groups of the " +
                    std::to_string(ranks) + " MPI ranks for " +
                    std::to_string(n_phases) +
                    " phase(s) (Loading/Number of phases): a group would "
                    "have no phase; use larger groups."));
      g    = rank / size;
      root = rank % size == 0;
      if (n == 1)
        group_comm = world;
      else
        {
          const int ierr = MPI_Comm_split(world, g, rank, &group_comm);
          AssertThrowMPI(ierr);
          owned = true;
        }
    }



    PhaseGroups::~PhaseGroups()
    {
      if (owned)
        MPI_Comm_free(&group_comm);
    }



    unsigned int
    PhaseGroups::group_of(const unsigned int phase) const
    {
      unsigned int group = 0;
      while (group + 1 < n && first_phase(group + 1) <= phase)
        ++group;
      return group;
    }



    StateCollector::StateCollector(const PhaseGroups &groups,
                                   const MPI_Comm     world)
      : groups(groups)
      , world_root(dealii::Utilities::MPI::this_mpi_process(world) == 0)
    {
      const int ierr = MPI_Comm_dup(world, &comm);
      AssertThrowMPI(ierr);
    }



    StateCollector::~StateCollector()
    {
      release_completed();
      // Only after an error: MPI may still read these buffers, so their
      // heap blocks are handed to vectors that are never destroyed (a move
      // keeps the block); the process ends in the error report.
      for (Send &s : sends)
        static_cast<void>(new std::vector<double>(std::move(s.buffer)));
      MPI_Comm_free(&comm);
    }



    void
    StateCollector::release_completed()
    {
      for (auto s = sends.begin(); s != sends.end();)
        {
          int done = 0;
          MPI_Test(&s->request, &done, MPI_STATUS_IGNORE);
          s = done != 0 ? sends.erase(s) : std::next(s);
        }
    }



    void
    StateCollector::submit(const results::StageState &state)
    {
      if (!groups.group_root())
        return;
      if (world_root)
        {
          own.push_back(state);
          return;
        }
      release_completed();
      sends.emplace_back();
      Send &s        = sends.back();
      s.buffer       = results::StateBuffer::pack(state);
      const int ierr = MPI_Isend(s.buffer.data(),
                                 static_cast<int>(s.buffer.size()),
                                 MPI_DOUBLE,
                                 0,
                                 state_tag,
                                 comm,
                                 &s.request);
      AssertThrowMPI(ierr);
    }



    std::vector<results::StageState>
    StateCollector::receive(const bool wait)
    {
      std::vector<results::StageState> states;
      states.swap(own);
      while (true)
        {
          int        arrived = 0;
          MPI_Status status;
          if (wait && states.empty())
            {
              const int ierr =
                MPI_Probe(MPI_ANY_SOURCE, state_tag, comm, &status);
              AssertThrowMPI(ierr);
              arrived = 1;
            }
          else
            {
              const int ierr =
                MPI_Iprobe(MPI_ANY_SOURCE, state_tag, comm, &arrived, &status);
              AssertThrowMPI(ierr);
            }
          if (arrived == 0)
            return states;
          int size = 0;
          MPI_Get_count(&status, MPI_DOUBLE, &size);
          std::vector<double> buffer(size);
          const int           ierr = MPI_Recv(buffer.data(),
                                    size,
                                    MPI_DOUBLE,
                                    status.MPI_SOURCE,
                                    state_tag,
                                    comm,
                                    MPI_STATUS_IGNORE);
          AssertThrowMPI(ierr);
          states.push_back(results::StateBuffer::unpack(buffer));
        }
    }



    void
    StateCollector::finish(const double busy_s)
    {
      if (!groups.group_root() || world_root)
        return;
      for (Send &s : sends)
        MPI_Wait(&s.request, MPI_STATUS_IGNORE);
      sends.clear();
      const int ierr = MPI_Send(&busy_s, 1, MPI_DOUBLE, 0, busy_tag, comm);
      AssertThrowMPI(ierr);
    }



    std::vector<double>
    StateCollector::busy_times(const double own_busy_s)
    {
      std::vector<double> busy(groups.n_groups(), own_busy_s);
      for (unsigned int group = 1; group < groups.n_groups(); ++group)
        {
          const int ierr = MPI_Recv(&busy[group],
                                    1,
                                    MPI_DOUBLE,
                                    groups.root_rank(group),
                                    busy_tag,
                                    comm,
                                    MPI_STATUS_IGNORE);
          AssertThrowMPI(ierr);
        }
      return busy;
    }
  } // namespace runs
} // namespace cycloid

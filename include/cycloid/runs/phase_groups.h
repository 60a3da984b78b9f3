#ifndef cycloid_runs_phase_groups_h
#define cycloid_runs_phase_groups_h

#include <cycloid/results/stage_state.h>

#include <list>
#include <vector>

#include <mpi.h>

namespace cycloid
{
  namespace runs
  {
    /**
     * @brief The ranks of a phase sweep split into groups of
     * `Loading/Ranks per phase group` ranks (MPI_Comm_split), each solving
     * a contiguous block of the phases on its own communicator.
     *
     * Contiguous blocks, not every G-th phase: within a group each phase
     * warm-starts from the group's previous phase, and neighbouring phases
     * (one step of the crank apart) share most of their active set, so
     * only the first phase of each block starts cold (from the analytical
     * model, as phase 1 of a one-group sweep does). Blocks differ in
     * length by at most one phase.
     */
    class PhaseGroups
    {
    public:
      /**
       * Split @p world into groups of @p ranks_per_group ranks (0: one
       * group of all ranks, which is then @p world itself) for @p n_phases
       * phases; group g holds world ranks g R ... g R + R - 1. Throws,
       * naming the entry, if the number of ranks is not a multiple of
       * @p ranks_per_group or makes more groups than phases (collective).
       */
      PhaseGroups(const MPI_Comm     world,
                  const unsigned int ranks_per_group,
                  const unsigned int n_phases);

      /** Free the groups' communicator (MPI_Comm_free does not
       * communicate, so this is safe while an error unwinds). */
      ~PhaseGroups();

      /** Not copyable: it owns a communicator. */
      PhaseGroups(const PhaseGroups &) = delete;
      /** Not copyable. */
      PhaseGroups &
      operator=(const PhaseGroups &) = delete;

      /** The communicator of this rank's group. */
      MPI_Comm
      comm() const
      {
        return group_comm;
      }

      /** Number of groups. */
      unsigned int
      n_groups() const
      {
        return n;
      }

      /** Ranks per group. */
      unsigned int
      group_size() const
      {
        return size;
      }

      /** This rank's group. */
      unsigned int
      group() const
      {
        return g;
      }

      /** Whether this rank is rank 0 of its group (it hands the group's
       * states to world rank 0). */
      bool
      group_root() const
      {
        return root;
      }

      /** The first phase of group @p group; its phases end before the
       * first phase of @p group + 1 (the number of phases for the last
       * group + 1). */
      unsigned int
      first_phase(const unsigned int group) const
      {
        return group * n_phases / n;
      }

      /** The group that solves phase @p phase. */
      unsigned int
      group_of(const unsigned int phase) const;

      /** World rank of the root of group @p group. */
      int
      root_rank(const unsigned int group) const
      {
        return group * size;
      }

    private:
      unsigned int size       = 1;
      unsigned int n          = 1;
      unsigned int g          = 0;
      unsigned int n_phases   = 1;
      bool         root       = true;
      bool         owned      = false;
      MPI_Comm     group_comm = MPI_COMM_NULL;
    };



    /**
     * @brief Brings the states each phase group solves to world rank 0,
     * the one writer of the sweep's files: the group roots send each
     * state as a flat buffer (results::StateBuffer) without waiting, and
     * world rank 0 takes whatever has arrived between its own states, in
     * arrival order (the sweep puts them in phase order). The messages go
     * over a duplicate of the world communicator, apart from every other
     * message of the run.
     */
    class StateCollector
    {
    public:
      /** The collector of @p groups of @p world (collective). */
      StateCollector(const PhaseGroups &groups, const MPI_Comm world);

      /** Free the communicator; the buffers of sends an error left pending
       * are leaked, as MPI may still read them. */
      ~StateCollector();

      /** Not copyable: it owns a communicator and sends in flight. */
      StateCollector(const StateCollector &) = delete;
      /** Not copyable. */
      StateCollector &
      operator=(const StateCollector &) = delete;

      /** Hand @p state to world rank 0 (group roots; no effect on the
       * other ranks). World rank 0 keeps its own states; other roots send
       * them without waiting. */
      void
      submit(const results::StageState &state);

      /** World rank 0: the states submitted or received since the last
       * call. With @p wait, blocks until there is at least one. */
      std::vector<results::StageState>
      receive(const bool wait);

      /** Group roots: wait until world rank 0 has every state sent, then
       * report this group's busy time @p busy_s [s] to it. */
      void
      finish(const double busy_s);

      /** World rank 0, after receiving every state: each group's busy
       * time [s], its own being @p own_busy_s. */
      std::vector<double>
      busy_times(const double own_busy_s);

    private:
      /** A send in flight and the buffer it reads. */
      struct Send
      {
        std::vector<double> buffer;
        MPI_Request         request = MPI_REQUEST_NULL;
      };

      /** Forget the sends that have completed. */
      void
      release_completed();

      const PhaseGroups               &groups;
      MPI_Comm                         comm = MPI_COMM_NULL;
      bool                             world_root;
      std::vector<results::StageState> own;
      std::list<Send>                  sends;
    };
  } // namespace runs
} // namespace cycloid

#endif

#ifndef cycloid_postprocess_solution_record_h
#define cycloid_postprocess_solution_record_h

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace cycloid
{
  namespace postprocess
  {
    /**
     * @brief The record `solution.pvd` of the solution files a run wrote
     * (ParaView opens it as one series): each entry a time (or state
     * number) and the name of its `.pvtu` file. Rewritten on rank 0 each
     * time an entry is added, so a run that stops early leaves a valid
     * record.
     */
    class SolutionRecord
    {
    public:
      /** The record of @p directory (rank 0 of @p comm writes it, unless
       * @p write_record is false: a phase group whose solution files
       * another rank's record lists, in phase order). */
      SolutionRecord(const std::string &directory,
                     const MPI_Comm     comm,
                     const bool         write_record = true)
        : directory(directory)
        , root(write_record &&
               dealii::Utilities::MPI::this_mpi_process(comm) == 0)
      {}

      /** The name of the solution file of state or step @p step, without
       * extension. */
      static std::string
      name(const unsigned int step)
      {
        return "solution-" + dealii::Utilities::int_to_string(step, 4);
      }

      /** Add @p pvtu at @p time and rewrite solution.pvd. */
      void
      add(const double time, const std::string &pvtu)
      {
        entries.emplace_back(time, pvtu);
        if (!root)
          return;
        std::ofstream pvd(directory + "/solution.pvd");
        dealii::DataOutBase::write_pvd_record(pvd, entries);
      }

      /** Replace the entries (a resumed run: the files written before the
       * checkpoint); solution.pvd is rewritten at the next add(). */
      void
      restore(const std::vector<std::pair<double, std::string>> &previous)
      {
        entries = previous;
      }

    private:
      const std::string                           directory;
      const bool                                  root;
      std::vector<std::pair<double, std::string>> entries;
    };
  } // namespace postprocess
} // namespace cycloid

#endif

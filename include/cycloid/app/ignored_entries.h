#ifndef cycloid_app_ignored_entries_h
#define cycloid_app_ignored_entries_h

#include <cycloid/parameters/run.h>

#include <map>
#include <string>
#include <vector>

namespace cycloid
{
  namespace app
  {
    /** What decides which entries a run reads: its mode and the parts of
     * the scene that switch entries on or off. */
    struct RunShape
    {
      /** The run mode. */
      parameters::RunParameters::Mode mode =
        parameters::RunParameters::Mode::analytic;
      /** Scene/Dimension. */
      unsigned int dimension = 2;
      /** Mesh/Contact refinement side = loaded: the mesh then depends on
       * the sign of the loads. */
      bool refine_loaded_side_only = false;
      /** Crank bearings/Model = needle. */
      bool needle_bearings = false;
    };

    /**
     * One line per entry that the parameter file sets (@p set_in_file,
     * "Subsection/Entry" to the value as written) and that a run of shape
     * @p shape does not read, e.g. "warning: Loading/Control = rotation is
     * ignored by Run = analytic (the analytic model is torque-controlled)".
     * The table of which mode reads what is in ignored_entries.cc, the one
     * place that knows it; an entry left out of the file is never named.
     */
    std::vector<std::string>
    ignored_entry_warnings(
      const RunShape                           &shape,
      const std::map<std::string, std::string> &set_in_file);

    /** The entries of every row of the table ("Subsection/Entry" or
     * "Subsection/" and an asterisk for a whole subsection), for the test that
     * each names a declared entry. */
    std::vector<std::string>
    ignored_entry_table();
  } // namespace app
} // namespace cycloid

#endif

#ifndef cycloid_parameters_run_h
#define cycloid_parameters_run_h

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace cycloid
{
  namespace parameters
  {
    /**
     * @brief Top-level entries: the run mode and the output directory.
     */
    struct RunParameters
    {
      /** The run modes of the executable. */
      enum class Mode
      {
        analytic,
        mesh,
        quasi_static,
        phase_sweep,
        transient,
        reduced,
        tolerance,
        profile
      };

      /** A run mode as the user sees it: its name in `Run` and one line
       * on what it does. */
      struct ModeEntry
      {
        Mode        mode;    ///< The mode.
        const char *name;    ///< Its name in the parameter file.
        const char *summary; ///< One line for `--help` and the prm text.
      };

      /** Every run mode, in the order `--help` lists them: the one table
       * that the `Run` selection, its documentation, the parse and
       * `--help` are made from (a mode added here is in all four). */
      static const std::vector<ModeEntry> &
      modes();

      /** The run modes as `--help` prints them: one indented line each. */
      static std::string
      mode_help();

      /** Selected run mode. */
      Mode mode = Mode::analytic;
      /** Name of the run mode as written in the parameter file. */
      std::string mode_name = "analytic";
      /** Output directory (created if missing). */
      std::string output_directory = "output";
      /** Write the VTU fields of every FE state. */
      bool write_solution = true;

      /** Whether the run mode is an FE run (mesh, quasi-static,
       * phase-sweep, transient, and reduced and tolerance, whose coarse
       * model is one). */
      bool
      fe() const
      {
        return mode != Mode::analytic && mode != Mode::profile;
      }

      /** Declare the top-level entries. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read the top-level entries. */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace parameters
} // namespace cycloid

#endif

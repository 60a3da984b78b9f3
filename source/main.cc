// cycloid-contact: the executable. Parses the command line and the
// parameter file, then hands over to the selected run mode; an error is
// reported once (app/error_report.h).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <cycloid/app/all_parameters.h>
#include <cycloid/app/error_report.h>
#include <cycloid/app/parameter_suggestions.h>
#include <cycloid/app/run.h>
#include <cycloid/process/heap.h>

#include <iostream>
#include <string>

namespace
{
  void
  print_usage(std::ostream &out)
  {
    out << "Usage: cycloid-contact [--help] [--print-parameters[=json]] "
           "[file.prm]\n"
           "  file.prm            parameter file (deal.II ParameterHandler "
           "syntax)\n"
           "  --print-parameters  write every parameter with its default and "
           "documentation\n"
           "                      (with file.prm: with the values the file "
           "gives, without running)\n"
           "  --print-parameters=json\n"
           "                      the same as JSON, with each entry's value "
           "and pattern (for\n"
           "                      scripts: a prm file read by deal.II)\n"
           "  --help              this text\n"
           "Run modes (set Run = ...):\n"
        << cycloid::parameters::RunParameters::mode_help()
        << "Outputs go to 'Output directory': stiffness.csv, pin_forces.csv, "
           "parameters.prm (see README.md).\n";
  }



  /** What the command line asks for. */
  struct CommandLine
  {
    /** The action. */
    enum class Action
    {
      run,
      help,
      print_parameters,
      print_parameters_json,
      bad
    } action = Action::run;
    /** The parameter file (Action::run). */
    std::string filename;
    /** Why the command line is bad (Action::bad). */
    std::string error;
  };



  CommandLine
  parse_command_line(const int argc, char *argv[])
  {
    CommandLine command;
    for (int i = 1; i < argc; ++i)
      {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h")
          return {CommandLine::Action::help, "", ""};
        if (arg == "--print-parameters")
          command.action = CommandLine::Action::print_parameters;
        else if (arg == "--print-parameters=json")
          command.action = CommandLine::Action::print_parameters_json;
        else if (!arg.empty() && arg[0] == '-')
          return {CommandLine::Action::bad,
                  "",
                  "unknown option '" + arg + "'."};
        else if (!command.filename.empty())
          return {CommandLine::Action::bad,
                  "",
                  "give one parameter file only."};
        else
          command.filename = arg;
      }
    if (command.filename.empty() && command.action == CommandLine::Action::run)
      return {CommandLine::Action::bad, "", "no parameter file given."};
    return command;
  }



  /** Do what @p command asks; return the exit status (errors throw). */
  int
  execute(const CommandLine &command)
  {
    const bool root =
      dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    switch (command.action)
      {
        case CommandLine::Action::help:
          if (root)
            print_usage(std::cout);
          return 0;
        case CommandLine::Action::print_parameters:
          case CommandLine::Action::print_parameters_json: {
            dealii::ParameterHandler prm;
            cycloid::app::AllParameters::declare_parameters(prm);
            if (!command.filename.empty())
              cycloid::app::parse_input_explained(prm, command.filename);
            const bool json =
              command.action == CommandLine::Action::print_parameters_json;
            if (root)
              prm.print_parameters(
                std::cout,
                (json ? dealii::ParameterHandler::JSON :
                        dealii::ParameterHandler::PRM) |
                  dealii::ParameterHandler::KeepDeclarationOrder);
            return 0;
          }
        case CommandLine::Action::bad:
          if (root)
            {
              std::cerr << "Error: " << command.error << '\n';
              print_usage(std::cerr);
            }
          return 2;
        case CommandLine::Action::run:
          break;
      }
    const auto parameters = cycloid::app::AllParameters::read(command.filename);
    cycloid::app::run(parameters, MPI_COMM_WORLD);
    return 0;
  }
} // namespace



int
main(int argc, char *argv[])
{
  // Before MPI: a restart after MPI_Init would leave the launcher waiting.
  cycloid::process::restart_with_huge_pages(argv);
  cycloid::process::release_freed_memory();
  // MPI lives outside the try block: the error report talks over MPI.
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  try
    {
      return execute(parse_command_line(argc, argv));
    }
  catch (...)
    {
      return cycloid::app::report_error(std::current_exception(),
                                        MPI_COMM_WORLD);
    }
}

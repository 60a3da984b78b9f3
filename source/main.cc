// cycloid-contact: the executable. Parses the command line and the
// parameter file, then hands over to the selected run mode.

#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <cycloid/app/all_parameters.h>
#include <cycloid/app/run.h>

#include <iostream>
#include <string>

namespace
{
  void
  print_usage(std::ostream &out)
  {
    out << "Usage: cycloid-contact [--help] [--print-parameters] [file.prm]\n"
           "  file.prm            parameter file (deal.II ParameterHandler "
           "syntax)\n"
           "  --print-parameters  write every parameter with its default and "
           "documentation\n"
           "  --help              this text\n"
           "Run modes (set Run = ...):\n"
           "  analytic      Hertz-based load distribution over the pins "
           "(seed or line-contact pair model)\n"
           "  mesh          write the FE mesh of the scene\n"
           "  quasi-static  FE contact at one crank angle and torque(s)\n"
           "  phase-sweep   FE contact over the meshing phases\n"
           "  transient     elastodynamics with contact\n"
           "Outputs go to 'Output directory': stiffness.csv, pin_forces.csv "
           "(see README.md).\n";
  }
} // namespace

int
main(int argc, char *argv[])
{
  try
    {
      dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
      const bool                               root =
        dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;

      std::string filename;
      for (int i = 1; i < argc; ++i)
        {
          const std::string arg = argv[i];
          if (arg == "--help" || arg == "-h")
            {
              if (root)
                print_usage(std::cout);
              return 0;
            }
          if (arg == "--print-parameters")
            {
              dealii::ParameterHandler prm;
              cycloid::app::AllParameters::declare_parameters(prm);
              if (root)
                prm.print_parameters(
                  std::cout,
                  dealii::ParameterHandler::PRM |
                    dealii::ParameterHandler::KeepDeclarationOrder);
              return 0;
            }
          if (!arg.empty() && arg[0] == '-')
            {
              if (root)
                {
                  std::cerr << "Error: unknown option '" << arg << "'.\n";
                  print_usage(std::cerr);
                }
              return 2;
            }
          AssertThrow(filename.empty(),
                      dealii::ExcMessage("give one parameter file only."));
          filename = arg;
        }
      if (filename.empty())
        {
          if (root)
            {
              std::cerr << "Error: no parameter file given.\n";
              print_usage(std::cerr);
            }
          return 2;
        }

      const auto parameters = cycloid::app::AllParameters::read(filename);
      cycloid::app::run(parameters, MPI_COMM_WORLD);
    }
  catch (dealii::ExceptionBase &exc)
    {
      std::cerr << "Error: ";
      exc.print_info(std::cerr);
      std::cerr << std::endl;
      return 1;
    }
  catch (std::exception &exc)
    {
      std::cerr << "Error: " << exc.what() << std::endl;
      return 1;
    }
  catch (...)
    {
      std::cerr << "Error: unknown exception." << std::endl;
      return 1;
    }
  return 0;
}

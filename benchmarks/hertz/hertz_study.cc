// Hertz verification study: runs the HertzCase (elastic cylinder against a
// convex cylinder or in a concave seat, plane strain) for the refinement
// levels given on the command line and prints one CSV row per level.
// Usage: hertz-study convex|concave FORCE DEGREE GLOBAL CONTACT [CONTACT ...]
// Environment: CYCLOID_FORMULATION=node-to-surface for the collocation
// variant (default mortar).
// (FORCE in N/mm)
// (benchmarks/hertz/run.py drives it and makes the figure).

#include <deal.II/base/mpi.h>

#include <cycloid/contact/hertz_case.h>

#include <cstdlib>
#include <iostream>
#include <string>

int
main(int argc, char *argv[])
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc < 6)
    {
      std::cerr << "usage: hertz-study convex|concave FORCE DEGREE GLOBAL "
                   "CONTACT [CONTACT ...]\n";
      return 2;
    }
  cycloid::contact::HertzCase c;
  c.concave = std::string(argv[1]) == "concave";
  c.force   = std::stod(argv[2]);
  if (const char *f = std::getenv("CYCLOID_FORMULATION"))
    if (std::string(f) == "node-to-surface")
      c.formulation = cycloid::contact::Formulation::node_to_surface;
  c.degree             = std::stoi(argv[3]);
  c.global_refinements = std::stoi(argv[4]);
  const bool root =
    dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  if (root)
    std::cout
      << "formulation,seat,force_N_per_mm,degree,global,contact,dofs,h_contact_mm,n_active,"
         "iterations,a_fe_mm,a_exact_mm,a_error,p0_fe_MPa,"
         "p0_exact_MPa,p0_error,force_balance_error,wall_s\n";
  for (int k = 5; k < argc; ++k)
    {
      c.contact_refinements = std::stoi(argv[k]);
      const auto r = cycloid::contact::run_hertz_case(c, MPI_COMM_WORLD);
      if (root)
        std::cout << (c.formulation == cycloid::contact::Formulation::mortar ?
                        "mortar" :
                        "node-to-surface")
                  << ',' << argv[1] << ',' << c.force << ',' << c.degree << ','
                  << c.global_refinements << ',' << c.contact_refinements << ','
                  << r.n_dofs << ',' << r.h_contact << ',' << r.n_active << ','
                  << r.iterations << ',' << r.half_width << ','
                  << c.half_width() << ',' << r.half_width / c.half_width() - 1
                  << ',' << r.peak_pressure << ',' << c.peak_pressure() << ','
                  << r.peak_pressure / c.peak_pressure() - 1 << ','
                  << r.transmitted_force / c.force - 1 << ',' << r.wall_s
                  << std::endl;
    }
  return 0;
}

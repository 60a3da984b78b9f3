// Elastic bar hitting a rigid wall (doc/design-basis.md §2.3): a bar of length
// L moving at v0 touches the wall at t = 0; 1D theory keeps it in contact
// for 2L/c with the force rho c A v0 and sends it back at -v0
// (c = sqrt(E/rho)). Plane strain with nu = 0 is exactly 1D here. The wall
// is a rigid cylinder of radius 1e6 L (flat to 1e-7 of the displacements).
//
// Usage: bar-impact SCHEME CELLS CFL [SPECTRAL_RADIUS]
//   SCHEME: newmark | contact-stabilised | generalized-alpha
//   CELLS:  cells along the bar (4 across); CFL = c dt / h.
// Prints one CSV row per step (t, contact force, momentum velocity,
// energies, balance, penetration) for 2.5 contact durations.
// (tests/check_bar_impact.py checks it; benchmarks/transient/run.py plots.)

#include <deal.II/base/mpi.h>

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/grid/grid_generator.h>

#include <cycloid/dynamics/contact_dynamics.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <string>

int
main(int argc, char *argv[])
{
  using namespace cycloid;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc < 4)
    {
      std::cerr << "usage: bar-impact SCHEME CELLS CFL [SPECTRAL_RADIUS]\n";
      return 2;
    }
  const MPI_Comm comm = MPI_COMM_WORLD;
  const bool     root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  try
    {
      dynamics::DynamicsSettings settings;
      settings.scheme          = dynamics::parse_scheme(argv[1]);
      const unsigned int cells = std::stoi(argv[2]);
      const double       cfl   = std::stod(argv[3]);
      if (argc > 4)
        settings.spectral_radius = std::stod(argv[4]);

      const double L = 10., h = 1., E = 200000., rho = 7850., v0 = 1000.;
      const double c         = std::sqrt(E / (rho * 1e-12)); // mm/s
      const double dt        = cfl * (L / cells) / c;
      const double T_contact = 2 * L / c;

      dealii::parallel::shared::Triangulation<2> tria(comm);
      dealii::GridGenerator::subdivided_hyper_rectangle(tria,
                                                        {cells, 4},
                                                        dealii::Point<2>(0, 0),
                                                        dealii::Point<2>(L, h));
      for (const auto &cell : tria.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            cell->face(f)->set_boundary_id(
              std::abs(cell->face(f)->center()[0] - L) < 1e-12 ? 1 : 0);

      contact::ContactSettings cs;
      cs.search_distance = 0.1;
      cs.solver          = elasticity::LinearSolver::cg_amg;
      contact::ContactProblem<2> problem(tria, 1, {{0, {E, 0., rho}}}, cs);
      const double               R = 1e6 * L;
      problem.set_contact({0},
                          1,
                          {{dealii::Point<2>(L + R, h / 2), R, 99, 99}},
                          false);
      problem.setup();
      problem.set_fixed_dofs({});
      problem.set_load({});

      // Initial velocity v0 along x.
      const auto                           &el = problem.elasticity();
      dealii::TrilinosWrappers::MPI::Vector v(el.locally_owned_dofs(), comm);
      for (const auto &cell : el.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            std::vector<dealii::types::global_dof_index> idx(
              el.finite_element().n_dofs_per_cell());
            cell->get_dof_indices(idx);
            for (unsigned int i = 0; i < idx.size(); ++i)
              if (el.finite_element().system_to_component_index(i).first == 0 &&
                  el.locally_owned_dofs().is_element(idx[i]))
                v[idx[i]] = v0;
          }
      v.compress(dealii::VectorOperation::insert);
      dealii::TrilinosWrappers::MPI::Vector vg(el.locally_owned_dofs(),
                                               el.locally_relevant_dofs(),
                                               comm);
      vg                = v;
      const double mass = rho * 1e-12 * L * h;

      dynamics::ContactDynamics<2> dyn(problem, settings);
      dyn.initialise(vg);
      const double E0 = 0.5 * mass * v0 * v0;
      if (root)
        std::cout << std::setprecision(10) << "# bar L " << L << " mm, c " << c
                  << " mm/s, dt " << dt << " s, contact time 2L/c " << T_contact
                  << " s, force rho c h v0 " << rho * 1e-12 * c * h * v0
                  << " N/mm, E0 " << E0 << " N mm\n"
                  << "step,time_s,contact_force_N_per_mm,velocity_mm_per_s,"
                     "kinetic_Nmm,elastic_Nmm,balance_error_Nmm,"
                     "max_penetration_mm,n_active,iterations\n";
      const unsigned int n_steps =
        static_cast<unsigned int>(std::ceil(2.5 * T_contact / dt));
      for (unsigned int step = 1; step <= n_steps; ++step)
        {
          const auto r =
            dyn.step(dt, false, 0., "bar impact step " + std::to_string(step));
          double force = 0;
          for (const unsigned int i : problem.active_set())
            force +=
              problem.slave_reactions()[i] * problem.slave_nodes()[i].normal;
          // Momentum velocity (M v) . e_x / m.
          const auto Mv = el.mass_times(dyn.velocity());
          double     p  = 0;
          for (const auto i : el.locally_owned_dofs())
            p += Mv[i] * v[i] / v0;
          p = dealii::Utilities::MPI::sum(p, comm);
          const double balance =
            r.kinetic + r.elastic - E0 - r.bore_work - r.contact_work;
          if (root)
            std::cout << step << ',' << step * dt << ',' << force << ','
                      << p / mass << ',' << r.kinetic << ',' << r.elastic << ','
                      << balance << ',' << r.max_penetration << ','
                      << problem.active_set().size() << ',' << r.iterations
                      << '\n';
        }
    }
  catch (const std::exception &e)
    {
      if (root)
        std::cerr << "bar-impact: " << e.what() << std::endl;
      return 1;
    }
  return 0;
}

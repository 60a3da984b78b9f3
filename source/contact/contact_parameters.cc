#include <cycloid/contact/contact_parameters.h>

namespace cycloid
{
  namespace contact
  {
    void
    ContactParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii::Patterns;
      prm.enter_subsection("Contact");
      {
        prm.declare_entry("Maximum active set iterations",
                          "100",
                          Integer(1, 10000),
                          "Iteration limit of the primal-dual active set per "
                          "load state [-]; reaching it ends the run with an "
                          "error naming the state.");
        prm.declare_entry("Search distance",
                          "0.1",
                          Double(0),
                          "Flank vertices closer than this to a pin surface "
                          "are contact candidates [mm] (the approach under "
                          "load is a few micrometres).");
        prm.declare_entry("Formulation",
                          "mortar",
                          Selection("mortar|node-to-surface"),
                          "Discretisation of the contact constraint: mortar "
                          "(gap and master displacement weighted with the "
                          "dual basis of the slave faces: smooth pressures, "
                          "exact action = reaction) or node-to-surface "
                          "(collocation at the slave nodes: cheaper set-up, "
                          "pressures oscillate on non-matching meshes; see "
                          "doc/contact.md).");
        prm.declare_entry("Residual tolerance",
                          "1e-6",
                          Double(1e-14, 1),
                          "Largest accepted equilibrium residual of a "
                          "converged state, |C^T f_int| / |f_int| (internal "
                          "forces condensed onto the free DoFs) [-]; above it "
                          "the run stops with an error instead of reporting "
                          "an unconverged state.");
      }
      prm.leave_subsection();
      prm.enter_subsection("Solver");
      {
        prm.declare_entry("Linear solver",
                          "cg-amg",
                          Selection("cg-amg|cg-amg-translations|direct"),
                          "Linear solver of each active-set iteration: CG "
                          "with ML AMG given the rigid-body modes, the same "
                          "with translations only (for studies), or a direct "
                          "solver (small problems).");
        prm.declare_entry("Relative tolerance",
                          "1e-10",
                          Double(1e-16, 1e-2),
                          "Relative residual tolerance of CG [-].");
      }
      prm.leave_subsection();
    }



    void
    ContactParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      max_active_set_iterations =
        prm.get_integer("Maximum active set iterations");
      search_distance    = prm.get_double("Search distance");
      residual_tolerance = prm.get_double("Residual tolerance");
      formulation        = prm.get("Formulation") == "mortar" ?
                             Formulation::mortar :
                             Formulation::node_to_surface;
      prm.leave_subsection();
      prm.enter_subsection("Solver");
      const std::string solver = prm.get("Linear solver");
      linear_solver            = solver == "direct" ?
                                   elasticity::LinearSolver::direct :
                                 solver == "cg-amg-translations" ?
                                   elasticity::LinearSolver::cg_amg_translations_only :
                                   elasticity::LinearSolver::cg_amg;
      solver_tolerance         = prm.get_double("Relative tolerance");
      prm.leave_subsection();
    }
  } // namespace contact
} // namespace cycloid

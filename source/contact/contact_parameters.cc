#include <cycloid/contact/contact_parameters.h>
#include <cycloid/parameters/or_auto.h>

#include <algorithm>

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
        prm.declare_entry("First active set",
                          "hertz",
                          Selection("hertz|overlap"),
                          "Where the first load state's active set starts: "
                          "the flank nodes that the analytical model's "
                          "rotation pushes into the pins, either only those "
                          "within the Hertz half-width of the analytical pin "
                          "force plus half a node spacing (at least one "
                          "spacing) from the unloaded contact point (hertz), "
                          "or all of them "
                          "(overlap, about twice as many on fine contact "
                          "meshes: more active-set iterations, the same "
                          "answer; doc/contact.md). Under Loading/Control = "
                          "rotation it is overlap. Later states start from "
                          "the state before.");
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
                          "solver on the matrix gathered to one rank (2D "
                          "problems): CHOLMOD's Cholesky factorisation, or "
                          "Amesos KLU if the matrix is not symmetric "
                          "positive definite. Measured on the 2D transient "
                          "example (139 k DoFs): KLU steps 1.5 times faster "
                          "than CG + AMG, and CHOLMOD 1.4 times faster than "
                          "KLU (doc/transient.md).");
        prm.declare_entry(
          "AMG hierarchy",
          "auto",
          Selection("auto|smoothed-V|plain-W"),
          "How ML builds the hierarchy of Linear solver = cg-amg: "
          "smoothed aggregation with a V-cycle (ML's default for "
          "elasticity), or plain (unsmoothed) aggregation with a W-cycle, "
          "whose prolongators are the tentative ones: no matrix products "
          "at the set-up and a hierarchy a fraction of the size. The same "
          "answer to CG's tolerance. auto: plain-W in 3D (measured on the "
          "3D seed case: peak memory x0.70, the whole run x0.95, CG "
          "iterations 486 against 452), smoothed-V in 2D (doc/solver-reuse.md). "
          "Ignored by the direct solver.");
        prm.declare_entry(
          "Direct solver",
          "auto",
          parameters::OrAuto(Selection(elasticity::factorisation_names())),
          "The sparse factorisation of Linear solver = direct and of the "
          "reduced model's condensation (one factorisation, every load case "
          "as one block): cholmod (Cholesky, simplicial, AMD ordering, on "
          "one rank), cholmod-supernodal (the same with dense blocks and "
          "METIS ordering, for 3D fill-in), mumps (MUMPS L D L^T of the "
          "symmetric positive definite matrix on every rank, sparse "
          "right-hand sides), mumps-unsymmetric (MUMPS L U: the solver before "
          "issue #49, for comparison), klu (L U on one rank). A Cholesky that "
          "finds the matrix not positive definite hands it to klu. auto: "
          "cholmod, except the 3D reduced condensation: mumps. Measured side "
          "by side (doc/solver-reuse.md, \"One direct-solver interface\"): "
          "the 3D reduced seed case takes 17 s and 2.3 GB on 2 ranks with "
          "mumps, 32 s and 3.2 GB with cholmod-supernodal, 25 s and 3.0 GB "
          "with mumps-unsymmetric; the 2D transient example's steps are "
          "fastest with cholmod (21 s, mumps 22 s, klu 31 s).");
        prm.declare_entry("Relative tolerance",
                          "1e-10",
                          Double(1e-16, 1e-2),
                          "Relative residual tolerance of CG [-]: every "
                          "state's last active-set iteration, whose set is "
                          "reported, solves to it.");
        prm.declare_entry(
          "Inner tolerance",
          "auto",
          parameters::OrAuto(Double(0, 1e-2)),
          "Relative residual tolerance of CG of the first solve while the "
          "active set of a static state still changes [-]; each further "
          "loose solve of the state is ten times tighter, down to 1e-6 (or "
          "this value if it is tighter); 0: Relative tolerance (every solve "
          "tight). Looser, those solves only decide the next set; when the "
          "set repeats, or moves by at most 1 % of its nodes, the next set "
          "is solved to Relative tolerance, and every set after it. Time "
          "steps always solve tight: their right-hand side is dominated by "
          "inertia, and a loose solve of it cannot decide contact. auto: "
          "1e-4 in 3D (measured on the 3D seed case: 0.69-0.80 of the time "
          "of a constant 1e-6, which took 0.7 of the time of tight "
          "solves), 0 in 2D (doc/solver-reuse.md).");
        prm.declare_entry("Preconditioner reuse",
                          "false",
                          Bool(),
                          "true: keep one sparsity pattern (room for every "
                          "contact candidate active) and the AMG hierarchy "
                          "over the active sets, load states and time steps "
                          "of a mesh, rebuilding the hierarchy only when CG "
                          "needs 1.5 times (+5) the iterations it took after "
                          "the last build. false (default): a new pattern and "
                          "hierarchy for every active set. Same answer either "
                          "way; measured, reuse saves the set-ups but the "
                          "wider pattern and the older hierarchy cost as much "
                          "in CG (2D 2-4 % faster, 3D 10 % slower; "
                          "doc/solver-reuse.md).");
        prm.declare_entry(
          "Contact Schur complement",
          "auto",
          parameters::OrAuto(Bool()),
          "With Linear solver = direct: true keeps one Cholesky "
          "factorisation of the operator with its supports (no contact) "
          "over the active sets, states and time steps, and solves each "
          "active set through the Schur complement of its contact rows "
          "(dense, one row per active node; the entries of the inverse at "
          "the contact DoFs are computed once per DoF and kept). Same "
          "results to rounding; false factorises the condensed matrix of "
          "every active set. auto: true in transient runs with Newmark or "
          "generalized-alpha (one operator for the whole run), false "
          "otherwise (a single state pays for its columns and saves "
          "little). Measured on the 2D transient example: 0.8-1.0 s a "
          "step instead of 1.6-1.7 (doc/transient.md). Ignored by the other "
          "linear solvers.");
        prm.declare_entry(
          "Contact Schur complement columns",
          "4000",
          Integer(2, 100000),
          "The most columns of the inverse that the Schur complement keeps "
          "(one per DoF that a contact row has touched) [-]; they take "
          "8 n^2 bytes on every rank (128 MB at 4000). Beyond it the least "
          "recently used are dropped down to half and computed again when "
          "needed: a long run moves its contacts along the flanks. The 2D "
          "transient example keeps about 1500.");
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
      first_set          = prm.get("First active set") == "hertz" ?
                             FirstActiveSet::hertz :
                             FirstActiveSet::overlap;
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
      const std::string direct = prm.get("Direct solver");
      direct_solver.reset();
      if (!parameters::is_auto(direct))
        direct_solver = elasticity::factorisation_from_string(direct);
      const std::string hierarchy = prm.get("AMG hierarchy");
      amg_hierarchy.reset();
      if (!parameters::is_auto(hierarchy))
        amg_hierarchy = hierarchy == "plain-W" ?
                          elasticity::AMGHierarchy::plain_w :
                          elasticity::AMGHierarchy::smoothed_v;
      solver_tolerance        = prm.get_double("Relative tolerance");
      const std::string inner = prm.get("Inner tolerance");
      inner_tolerance =
        parameters::is_auto(inner) ? automatic : std::stod(inner);
      reuse_preconditioner    = prm.get_bool("Preconditioner reuse");
      const std::string schur = prm.get("Contact Schur complement");
      schur_complement.reset();
      if (!parameters::is_auto(schur))
        schur_complement = schur == "true";
      schur_columns = prm.get_integer("Contact Schur complement columns");
      prm.leave_subsection();
    }
  } // namespace contact
} // namespace cycloid

#include <deal.II/base/exceptions.h>

#include <deal.II/base/utilities.h>

#include <cycloid/mesh/mesh_parameters.h>
#include <cycloid/parameters/or_auto.h>

namespace cycloid
{
  namespace mesh
  {
    void
    MeshParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii::Patterns;
      prm.enter_subsection("Mesh");
      {
        prm.declare_entry("Contact element size",
                          "0.25",
                          Double(1e-4),
                          "Element size at the contact points (closest "
                          "points of every pin and disc) [mm].");
        prm.declare_entry("Fine zone radius",
                          "0.3",
                          Double(0),
                          "Radius around each contact point meshed with the "
                          "contact element size [mm].");
        prm.declare_entry("Size grading",
                          "0.25",
                          Double(0.01, 10),
                          "Growth of the element size with the distance from "
                          "the nearest contact point [mm per mm].");
        prm.declare_entry("Flank element size",
                          "1",
                          Double(1e-4),
                          "Largest element size in the toothed ring of a "
                          "disc [mm]; keeps the coarse mesh on the profile.");
        prm.declare_entry("Pin element size",
                          "1",
                          Double(1e-4),
                          "Largest element size in a pin [mm].");
        prm.declare_entry("Coarse element size",
                          "6",
                          Double(1e-4),
                          "Largest element size anywhere (disc interior, "
                          "housing) [mm].");
        prm.declare_entry("Axial layers per disc",
                          "3",
                          Integer(1, 1000),
                          "3D: element layers through the width of one disc "
                          "[-].");
        prm.declare_entry("Axial layers in the gap",
                          "1",
                          Integer(1, 1000),
                          "3D: element layers of pins and housing across the "
                          "axial gap between the discs [-].");
        prm.declare_entry("Global refinements",
                          "0",
                          Integer(0, 10),
                          "Global refinements of the gmsh mesh in deal.II "
                          "[-].");
        prm.declare_entry("Contact refinements",
                          "0",
                          Integer(0, 20),
                          "A-priori refinements of the cells within Contact "
                          "refinement radius of a contact point [-].");
        prm.declare_entry("Contact refinement radius",
                          "0.5",
                          Double(0),
                          "Radius of the a-priori contact refinement [mm].");
        prm.declare_entry(
          "Contact refinement side",
          "both",
          Selection("both|loaded"),
          "Where the a-priori Contact refinements act: at the contact "
          "point of every pin (both), or only at the pins whose moment arm "
          "resists the load, arm x sign(load) >= -5 % of the largest arm "
          "(loaded; the pins that can engage, about half of them; with "
          "loads of both signs in one run it falls back to both). The gmsh "
          "size field is the same either way [-].");
        prm.declare_entry("Polynomial degree",
                          "1",
                          Integer(1, 2),
                          "Degree p of the Q_p displacement elements (and of "
                          "the mapping that follows the exact curves) [-]. "
                          "Contact nodes are all support points of the "
                          "flank faces (tensor-product Q2 face weights are "
                          "positive, so node-based contact stays valid).");
        prm.declare_entry("Adaptive refinement cycles",
                          "0",
                          Integer(0, 10),
                          "Quasi-static FE runs: after solving a state, refine "
                          "the cells (of every body) next to the active "
                          "contact nodes and solve again, this many times "
                          "[-]. Adds to the a-priori Contact refinements.");
        prm.declare_entry(
          "Error estimate",
          "auto",
          Selection("auto|true|false"),
          "FE states: solve each state also with the mesh's finest contact "
          "level coarsened once and twice, and report the larger of the "
          "last change and half the change before it as the state's error "
          "estimate (stiffness.csv K_secant_error, K_tangent_error, "
          "max_pin_force_error; pin_forces.csv Fn_error_N). A mesh with "
          "fewer than 2 Contact refinements is refined to 2. auto: on in "
          "2D (the coarser solves add 8-46 %), off in 3D (there the "
          "coarser levels have most of the DoFs and cost nearly as much as "
          "the state) unless Target accuracy is set [-].");
        prm.declare_entry(
          "Bulk error estimate",
          "auto",
          Selection("auto|true|false"),
          "FE states with an error estimate: add the error of the bulk mesh "
          "(every cell below the two finest levels, which the contact "
          "levels' estimate leaves as it is: the global refinement level "
          "and the graded halo around the contacts), twice the change of "
          "K_secant, K_tangent and every pin force when the state is solved "
          "once more with every such cell refined once. In 2D at the "
          "default element sizes that part is 0.6-1.4 %, mostly K_tangent "
          "at low torque (1.2 % off against Q2 there). Measured on the "
          "first mesh, which Target accuracy's cycles aim at with it, and "
          "again on the last mesh after cycles. The extra solve has 2.6 "
          "(first mesh) to 3.7 (after cycles) times the DoFs in 2D, about "
          "eight times the bulk DoFs in 3D. A target below this part is "
          "not reached, and the run names the cure. true needs Error "
          "estimate. auto: on in 2D wherever the error is estimated, off "
          "in 3D (there the extra solve costs several times the state) "
          "[-].");
        prm.declare_entry("Warning threshold",
                          "0.02",
                          Double(0, 1),
                          "FE states whose largest error estimate exceeds "
                          "this are flagged (console warning naming the "
                          "pins, stiffness.csv mesh_warning = 1) [relative, "
                          "0.02 = 2 %].");
        prm.declare_entry(
          "Target accuracy",
          "auto",
          parameters::OrAuto(Double(0, 1)),
          "FE states: refine at the active contacts and solve again until "
          "every error estimate is below this, at most Maximum accuracy "
          "cycles times per state (0: off; needs Error estimate). auto: "
          "the Warning threshold in 2D quasi-static runs and phase sweeps "
          "(so that a default run is not one the warning flags), 0 in 3D "
          "(there each cycle costs minutes: set it explicitly) and in the "
          "other run modes [relative, 0.01 = 1 %].");
        prm.declare_entry("Maximum accuracy cycles",
                          "4",
                          Integer(1, 10),
                          "Refinement cycles that Target accuracy may add "
                          "to one state [-].");
        prm.declare_entry(
          "Maximum sweep refinements",
          "2",
          Integer(0, 6),
          "Phase sweeps with a Target accuracy set to a number (auto does "
          "not repeat: a repeat refines every phase and costs minutes in "
          "2D): how many times the whole sweep may be repeated while a "
          "K_tangent fluctuation over the period is not resolved (below twice its noise floor, "
          "fluctuation.csv); each repeat refines every phase one contact "
          "level beyond the finest phase of the pass before and takes the "
          "change between the passes as the floor; the repeats stop early "
          "when the floor falls too slowly to get there (0: never "
          "repeat) [-].");
        prm.declare_entry("Periodic meshes",
                          "true",
                          Bool(),
                          "Mesh crank angle psi as psi mod 360/zp turned by "
                          "whole pin pitches (pins relabelled), so that "
                          "states one mesh period apart have identical "
                          "meshes and the FE stiffness is periodic to "
                          "round-off. Only applies without crank holes "
                          "(Geometry/Number of crank holes = 0): crank holes "
                          "break the discs' tooth symmetry and with them the "
                          "exact periodicity of the stage.");
        prm.declare_entry(
          "Triangulation",
          "shared",
          Selection("shared|distributed"),
          "How the mesh is held on several MPI ranks. shared: every rank "
          "holds every cell (parallel::shared::Triangulation), METIS "
          "partitions them. distributed: p4est "
          "(parallel::distributed::Triangulation) with the gmsh mesh as "
          "its coarse grid on every rank and each refined cell on one rank "
          "(and a ghost layer), so the refined mesh and the DoF handler "
          "divide over the ranks; contact nodes, master faces and ties are "
          "gathered on every rank. Same results to round-off (the "
          "partition differs). Used by the quasi-static, phase-sweep, "
          "transient and reduced runs; Run = mesh always writes the shared "
          "mesh; the contact Schur complement needs shared [-].");
        prm.declare_entry("Write msh",
                          "false",
                          Bool(),
                          "Also write the gmsh mesh with its physical groups "
                          "as stage.msh in the output directory.");
      }
      prm.leave_subsection();
    }



    void
    MeshParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh");
      {
        contact_size              = prm.get_double("Contact element size");
        fine_radius               = prm.get_double("Fine zone radius");
        grading                   = prm.get_double("Size grading");
        flank_size                = prm.get_double("Flank element size");
        pin_size                  = prm.get_double("Pin element size");
        coarse_size               = prm.get_double("Coarse element size");
        axial_layers              = prm.get_integer("Axial layers per disc");
        gap_layers                = prm.get_integer("Axial layers in the gap");
        global_refinements        = prm.get_integer("Global refinements");
        contact_refinements       = prm.get_integer("Contact refinements");
        contact_refinement_radius = prm.get_double("Contact refinement radius");
        refine_loaded_side_only =
          prm.get("Contact refinement side") == "loaded";
        write_msh       = prm.get_bool("Write msh");
        distributed     = prm.get("Triangulation") == "distributed";
        degree          = prm.get_integer("Polynomial degree");
        periodic        = prm.get_bool("Periodic meshes");
        adaptive_cycles = prm.get_integer("Adaptive refinement cycles");
        const std::string estimate = prm.get("Error estimate");
        error.mode = estimate == "auto" ? ErrorControl::Mode::automatic :
                     estimate == "true" ? ErrorControl::Mode::on :
                                          ErrorControl::Mode::off;
        const std::string bulk   = prm.get("Bulk error estimate");
        error.automatic_bulk     = bulk == "auto";
        error.bulk               = bulk == "true";
        error.warning_threshold  = prm.get_double("Warning threshold");
        const std::string target = prm.get("Target accuracy");
        error.automatic_target   = parameters::is_auto(target);
        error.target_accuracy    = error.automatic_target ?
                                     0 :
                                     dealii::Utilities::string_to_double(target);
        error.max_cycles         = prm.get_integer("Maximum accuracy cycles");
        error.max_sweep_refinements =
          prm.get_integer("Maximum sweep refinements");
      }
      prm.leave_subsection();
      AssertThrow(contact_size <= flank_size && flank_size <= coarse_size,
                  dealii::ExcMessage(
                    "Mesh: need Contact element size <= Flank element size "
                    "<= Coarse element size."));
      AssertThrow(
        error.mode != ErrorControl::Mode::off || error.target_accuracy == 0,
        dealii::ExcMessage(
          "Mesh: Target accuracy needs Error estimate = auto or true."));
      AssertThrow(
        error.mode != ErrorControl::Mode::off || !error.bulk,
        dealii::ExcMessage(
          "Mesh: Bulk error estimate = true needs Error estimate = auto or "
          "true."));
      AssertThrow(contact_size <= pin_size,
                  dealii::ExcMessage("Mesh: need Contact element size <= Pin "
                                     "element size."));
    }
  } // namespace mesh
} // namespace cycloid

#include <cycloid/parameters/or_auto.h>
#include <cycloid/reduced/reduced_parameters.h>

namespace cycloid
{
  namespace reduced
  {
    void
    ReducedParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii::Patterns;
      prm.enter_subsection("Reduced");
      {
        prm.declare_entry(
          "Contact refinements",
          "auto",
          parameters::OrAuto(Integer(0, 6)),
          "Run = reduced: a-priori refinements of the coarse FE model at the "
          "loaded pins, within max(Mesh/Contact refinement radius, 2 w) of "
          "each contact point [-], 0 to 6; auto: 2 in 2D, 0 in 3D. Replaces "
          "Mesh/Contact refinements; the other Mesh entries (element sizes, "
          "degree) apply to the coarse model.");
        prm.declare_entry(
          "Load half-width",
          "auto",
          parameters::OrAuto(Double(1e-3, 5)),
          "Run = reduced: half-width w of the semi-elliptic pressure that "
          "loads the coarse model at each contact to measure its compliance "
          "[mm], 0.001 to 5; auto: 4 elements at the contact (Mesh/Contact "
          "element size / 2^Contact refinements * 4: 0.25 mm in 2D, 1 mm in "
          "3D at the default mesh), at most Geometry/Pin radius / 3. The "
          "analytic line-"
          "contact law turns the response to width w into the response to "
          "the Hertz width of the actual force, so the result does not "
          "depend on w as long as the mesh resolves it.");
        prm.declare_entry("Axial layers per disc",
                          "1",
                          Integer(1, 100),
                          "Run = reduced, 3D: element layers through the "
                          "width of each disc in the coarse model [-], 1 to "
                          "100 (replaces Mesh/Axial layers per disc; 2 "
                          "changes K by 0.1 %, doc/reduced-model.md).");
        prm.declare_entry(
          "Anchor angles",
          "3",
          Integer(0, 100),
          "Run = reduced over several crank angles: condense the coarse "
          "model at this many crank angles spread over the sweep (first and "
          "last included) and interpolate the compliance between them; the "
          "load distribution is solved exactly at every crank angle [-], 0 "
          "to 100; 0 (or at least the number of crank angles): condense at "
          "every crank angle. One mesh period moves a contact about 0.5 mm "
          "along its flank; 3 anchors reproduce condensing at every angle to "
          "0.1 % (doc/reduced-model.md).");
        prm.declare_entry("Axial slices per disc",
                          "2",
                          Integer(1, 50),
                          "Run = reduced, 3D: slices of each disc's width, "
                          "each with its own contact force per pin [-], 1 "
                          "to 50 (the load along the width follows the "
                          "pins' bending and the discs' tilt).");
        prm.declare_entry(
          "Error estimate",
          "true",
          Bool(),
          "Run = reduced: estimate every state's error (stiffness.csv "
          "K_secant_error, K_tangent_error, max_pin_force_error; "
          "pin_forces.csv Fn_error_N) from the change against the same state "
          "on a companion coarse model one level coarser: one contact "
          "refinement fewer, or in-plane element sizes doubled where there "
          "is none, the load half-width following, and half the axial "
          "slices. States above Mesh/Warning threshold are flagged "
          "(mesh_warning = 1). Costs about a third more in 3D and little in "
          "2D; false: no estimate, and the same results otherwise.");
      }
      prm.leave_subsection();
    }



    void
    ReducedParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Reduced");
      const std::string cr = prm.get("Contact refinements");
      contact_refinements = parameters::is_auto(cr) ? automatic : std::stoi(cr);
      const std::string w = prm.get("Load half-width");
      load_half_width     = parameters::is_auto(w) ? 0. : std::stod(w);
      axial_layers        = prm.get_integer("Axial layers per disc");
      axial_slices        = prm.get_integer("Axial slices per disc");
      anchor_angles       = prm.get_integer("Anchor angles");
      error_estimate      = prm.get_bool("Error estimate");
      prm.leave_subsection();
    }
  } // namespace reduced
} // namespace cycloid

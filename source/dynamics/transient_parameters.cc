#include <deal.II/base/exceptions.h>

#include <cycloid/dynamics/transient_parameters.h>

namespace cycloid
{
  namespace dynamics
  {
    Scheme
    parse_scheme(const std::string &name)
    {
      if (name == "newmark")
        return Scheme::newmark;
      if (name == "contact-stabilised")
        return Scheme::contact_stabilised;
      if (name == "generalized-alpha")
        return Scheme::generalized_alpha;
      AssertThrow(false,
                  dealii::ExcMessage("Transient/Scheme: unknown scheme '" +
                                     name +
                                     "' (newmark | contact-stabilised | "
                                     "generalized-alpha)."));
      return Scheme::newmark;
    }



    void
    TransientParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using dealii::Patterns::Bool;
      using dealii::Patterns::Double;
      using dealii::Patterns::Integer;
      using dealii::Patterns::Selection;
      const TransientParameters d;
      prm.enter_subsection("Transient");
      {
        prm.declare_entry(
          "Scheme",
          d.scheme_name,
          Selection("newmark|contact-stabilised|generalized-alpha"),
          "Time scheme: 'newmark' (trapezoidal rule, contact on the "
          "displacements: energy-conserving without contact, chatters at "
          "contact), 'contact-stabilised' (Deuflhard-Krause-Ertel 2008: the "
          "predictor is projected onto the admissible set in the mass norm "
          "before the implicit step; dissipates at contact, never gains), "
          "'generalized-alpha' (Chung-Hulbert, with Spectral radius).");
        prm.declare_entry("Spectral radius",
                          std::to_string(d.spectral_radius),
                          Double(0., 1.),
                          "Generalized-alpha spectral radius at infinite "
                          "frequency rho_inf [-], in [0, 1]; 1: no numerical "
                          "damping (trapezoidal rule).");
        prm.declare_entry("Time step",
                          "1e-5",
                          Double(1e-12, 1.),
                          "Time step [s].");
        prm.declare_entry("End time",
                          "1e-3",
                          Double(0., 1e3),
                          "End time [s]; the run starts at t = 0 at rest, "
                          "undeformed, at Loading/Crank angle.");
        prm.declare_entry("Crank speed",
                          std::to_string(d.crank_speed),
                          Double(-1e7, 1e7),
                          "Crank (input) speed [deg/s]; the discs are placed "
                          "kinematically at the crank angle of each step "
                          "(9000 deg/s = 1500 rpm). 0: the discs stay.");
        prm.declare_entry(
          "Ramp time",
          "2e-4",
          Double(0., 1e3),
          "The torque rises as T (1 - cos(pi t / t_r)) / 2 over "
          "this time [s], then stays; 0: applied at once.");
        prm.declare_entry("Rayleigh mass damping",
                          "0",
                          Double(0., 1e9),
                          "Rayleigh damping C = a M + b K: a [1/s].");
        prm.declare_entry("Rayleigh stiffness damping",
                          "0",
                          Double(0., 1.),
                          "Rayleigh damping C = a M + b K: b [s].");
        prm.declare_entry("Output interval",
                          "0",
                          Integer(0),
                          "Write solution-NNNN.pvtu every this many steps and "
                          "list them in solution.pvd (0: no VTU) [-].");
        prm.declare_entry("Checkpoint interval",
                          "0",
                          Integer(0),
                          "Write a checkpoint (checkpoint.*) every this many "
                          "steps (0: none) [-].");
        prm.declare_entry("Resume",
                          "false",
                          Bool(),
                          "Continue from the checkpoint in the output "
                          "directory (same prm, same number of MPI ranks).");
        prm.declare_entry(
          "Maximum energy error",
          "0.5",
          Double(0., 1e6),
          "The run stops with an error when |E_kin + E_el + D - E_0 - W| "
          "exceeds this fraction of the largest energy level so far, max(E_kin + "
          "E_el + D, |W|) (plain "
          "Newmark chattering at contact gains energy) [-]; a warning is "
          "printed from 5 %.");
        prm.declare_entry(
          "Stop after step",
          "0",
          Integer(0),
          "End the run after this step (0: run to End time); "
          "with a checkpoint, emulates an interrupted run [-].");
      }
      prm.leave_subsection();
    }



    void
    TransientParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Transient");
      {
        scheme_name         = prm.get("Scheme");
        scheme              = parse_scheme(scheme_name);
        spectral_radius     = prm.get_double("Spectral radius");
        time_step           = prm.get_double("Time step");
        end_time            = prm.get_double("End time");
        crank_speed         = prm.get_double("Crank speed");
        ramp_time           = prm.get_double("Ramp time");
        rayleigh_mass       = prm.get_double("Rayleigh mass damping");
        rayleigh_stiffness  = prm.get_double("Rayleigh stiffness damping");
        output_interval     = prm.get_integer("Output interval");
        checkpoint_interval = prm.get_integer("Checkpoint interval");
        resume              = prm.get_bool("Resume");
        stop_after_step     = prm.get_integer("Stop after step");
        max_energy_error    = prm.get_double("Maximum energy error");
      }
      prm.leave_subsection();
    }
  } // namespace dynamics
} // namespace cycloid

#ifndef cycloid_dynamics_transient_parameters_h
#define cycloid_dynamics_transient_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace cycloid
{
  namespace dynamics
  {
    /** Time schemes of ContactDynamics (`Transient/Scheme`). */
    enum class Scheme
    {
      /** Trapezoidal rule (beta = 1/4, gamma = 1/2), contact enforced on
       * the displacement at the end of the step. */
      newmark,
      /** Deuflhard-Krause-Ertel (2008): the predictor u_n + dt v_n is
       * projected onto the admissible set in the mass norm, then an
       * implicit trapezoidal step from the projected predictor; the contact
       * force of the previous step is dropped. */
      contact_stabilised,
      /** Chung-Hulbert generalized-alpha with a spectral radius. */
      generalized_alpha
    };

    /** The scheme named by @p name (as in prm subsection Transient). */
    Scheme
    parse_scheme(const std::string &name);

    /**
     * @brief Time integration of elastodynamics with contact (subsection
     * `Transient`): scheme, step, crank speed, load ramp, damping, output
     * and checkpoint intervals. Used by `Run = transient` and by the
     * transient verification driver.
     */
    struct TransientParameters
    {
      /** The time scheme. */
      Scheme scheme = Scheme::contact_stabilised;
      /** Its name as in the prm: newmark | contact-stabilised |
       * generalized-alpha. */
      std::string scheme_name = "contact-stabilised";
      /** Spectral radius at infinite frequency of generalized-alpha [-]. */
      double spectral_radius = 0.8;
      /** Time step [s]. */
      double time_step = 1e-5;
      /** End time [s]. */
      double end_time = 1e-3;
      /** Crank speed [deg/s]; the disc placement follows the crank. */
      double crank_speed = 9000.;
      /** Time over which the torque rises (smoothly) to its value [s]. */
      double ramp_time = 2e-4;
      /** Rayleigh damping C = a M + b K: a [1/s]. */
      double rayleigh_mass = 0.;
      /** Rayleigh damping C = a M + b K: b [s]. */
      double rayleigh_stiffness = 0.;
      /** VTU output every this many steps (0: none) [-]. */
      unsigned int output_interval = 0;
      /** Checkpoint every this many steps (0: none) [-]. */
      unsigned int checkpoint_interval = 0;
      /** Resume from the checkpoint in the output directory. */
      bool resume = false;
      /** Largest |energy balance error| / work before the run stops [-]. */
      double max_energy_error = 0.5;
      /** Stop after this step (0: at the end time); for interrupted runs. */
      unsigned int stop_after_step = 0;

      /** Declare the entries of subsection `Transient`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsection `Transient`. */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace dynamics
} // namespace cycloid

#endif

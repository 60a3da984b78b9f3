#ifndef cycloid_dynamics_contact_stabilised_h
#define cycloid_dynamics_contact_stabilised_h

#include <cycloid/dynamics/time_scheme.h>

namespace cycloid
{
  namespace dynamics
  {
    /**
     * @brief Deuflhard-Krause-Ertel (2008), `Transient/Scheme =
     * contact-stabilised`: the predictor u_n + dt v_n is projected onto the
     * admissible set in the mass norm, then an implicit trapezoidal step
     * runs from the projected predictor u~. The projection absorbs the
     * contact force of t_n, which is what keeps the scheme from chattering
     * (and from gaining energy) at contact.
     *
     * The multipliers of the trapezoidal step are the sum of the contact
     * forces at t_n and t_{n+1}; the scheme reports half of them, the step
     * average that carries the impulse, which is then also the step's force
     * on moving obstacles. The acceleration is not part of its state.
     */
    template <int dim>
    class ContactStabilised : public TimeScheme<dim>
    {
    public:
      /** With Rayleigh damping C = @p rayleigh_mass M + @p rayleigh_stiffness
       * K. */
      ContactStabilised(const double rayleigh_mass,
                        const double rayleigh_stiffness);

      /** The projection, then the trapezoidal step. */
      StepOutcome
      step(contact::ContactProblem<dim> &contact,
           const StepInput              &in) const override;

      /** @p new_force: the step average. */
      double
      obstacle_force(const double old_force,
                     const double new_force) const override;

    private:
      /** Solve the mass-norm projection of the predictor (its displacement
       * is then @p contact's). */
      contact::ContactState
      project_predictor(contact::ContactProblem<dim> &contact,
                        const StepInput              &in) const;

      /** The load surface's rotation at the predictor: beta_n + dt
       * dbeta/dt. */
      double
      predicted_rotation(const contact::ContactProblem<dim> &contact,
                         const StepInput                    &in) const;

      /** Effective operator and history loads of the trapezoidal step from
       * the projected predictor @p tilde (owned). */
      elasticity::DynamicTerms
      trapezoidal_terms(
        const contact::ContactProblem<dim>          &contact,
        const StepInput                             &in,
        const dealii::TrilinosWrappers::MPI::Vector &tilde) const;

      const double aR; ///< Rayleigh damping of the mass [1/s].
      const double bR; ///< Rayleigh damping of the stiffness [s].
    };
  } // namespace dynamics
} // namespace cycloid

#endif

#ifndef cycloid_dynamics_newmark_h
#define cycloid_dynamics_newmark_h

#include <cycloid/dynamics/time_scheme.h>

namespace cycloid
{
  namespace dynamics
  {
    /**
     * The coefficients of the generalized-alpha family: the equation of
     * motion is taken at t_{n+1-alpha_f} (elastic, damping and load terms)
     * and t_{n+1-alpha_m} (inertia), u and v follow Newmark's formulas
     * with beta and gamma. The defaults are the trapezoidal rule (plain
     * Newmark).
     */
    struct AlphaCoefficients
    {
      double alpha_m = 0;    ///< Weight of a_n in the inertia term [-].
      double alpha_f = 0;    ///< Weight of t_n in the other terms [-].
      double beta    = 0.25; ///< Newmark beta [-].
      double gamma   = 0.5;  ///< Newmark gamma [-].

      /** Chung-Hulbert (1993): second order with the spectral radius
       * @p rho at infinite frequency (1: no dissipation, 0: the largest). */
      static AlphaCoefficients
      from_spectral_radius(const double rho);
    };

    /**
     * @brief Generalized-alpha (`Transient/Scheme = generalized-alpha`):
     * one contact problem per step, the alpha-weighted equation of motion
     * with contact enforced on the displacement at the end of the step.
     *
     * The multipliers are the contact forces of the alpha-weighted
     * equation, i.e. at t_{n+1-alpha_f}, inside the step: they are the
     * step's force on moving obstacles as they are.
     */
    template <int dim>
    class GeneralizedAlpha : public TimeScheme<dim>
    {
    public:
      /** With @p coefficients and Rayleigh damping C = @p rayleigh_mass M +
       * @p rayleigh_stiffness K. */
      GeneralizedAlpha(const AlphaCoefficients &coefficients,
                       const double             rayleigh_mass,
                       const double             rayleigh_stiffness);

      /** The alpha-weighted Newmark step; its acceleration is part of the
       * state. */
      StepOutcome
      step(contact::ContactProblem<dim> &contact,
           const StepInput              &in) const override;

      /** @p new_force: the force at t_{n+1-alpha_f}. */
      double
      obstacle_force(const double old_force,
                     const double new_force) const override;

    private:
      /** Effective operator and history loads of the step from u_n, v_n,
       * a_n in @p in and the displacement predictor @p uh. */
      elasticity::DynamicTerms
      dynamic_terms(const contact::ContactProblem<dim>          &contact,
                    const StepInput                             &in,
                    const dealii::TrilinosWrappers::MPI::Vector &uh) const;

      const double am; ///< alpha_m.
      const double af; ///< alpha_f.
      const double b;  ///< Newmark beta.
      const double g;  ///< Newmark gamma.
      const double aR; ///< Rayleigh damping of the mass [1/s].
      const double bR; ///< Rayleigh damping of the stiffness [s].
    };

    /**
     * @brief Newmark's trapezoidal rule (`Transient/Scheme = newmark`):
     * generalized-alpha with alpha_m = alpha_f = 0, beta = 1/4, gamma = 1/2.
     *
     * Its multipliers are the contact forces at t_{n+1}, so the step's
     * force on moving obstacles is the trapezoid of the forces at t_n and
     * t_{n+1}.
     */
    template <int dim>
    class Newmark : public GeneralizedAlpha<dim>
    {
    public:
      /** With Rayleigh damping C = @p rayleigh_mass M + @p rayleigh_stiffness
       * K. */
      Newmark(const double rayleigh_mass, const double rayleigh_stiffness);

      /** (@p old_force + @p new_force) / 2. */
      double
      obstacle_force(const double old_force,
                     const double new_force) const override;
    };
  } // namespace dynamics
} // namespace cycloid

#endif

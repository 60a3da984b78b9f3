#include <cycloid/dynamics/newmark.h>

namespace cycloid
{
  namespace dynamics
  {
    using Vector = dealii::TrilinosWrappers::MPI::Vector;

    AlphaCoefficients
    AlphaCoefficients::from_spectral_radius(const double rho)
    {
      AlphaCoefficients c;
      c.alpha_m = (2. * rho - 1.) / (rho + 1.);
      c.alpha_f = rho / (rho + 1.);
      c.gamma   = 0.5 - c.alpha_m + c.alpha_f;
      c.beta =
        0.25 * (1. - c.alpha_m + c.alpha_f) * (1. - c.alpha_m + c.alpha_f);
      return c;
    }



    template <int dim>
    GeneralizedAlpha<dim>::GeneralizedAlpha(
      const AlphaCoefficients &coefficients,
      const double             rayleigh_mass,
      const double             rayleigh_stiffness)
      : am(coefficients.alpha_m)
      , af(coefficients.alpha_f)
      , b(coefficients.beta)
      , g(coefficients.gamma)
      , aR(rayleigh_mass)
      , bR(rayleigh_stiffness)
    {}



    template <int dim>
    elasticity::DynamicTerms
    GeneralizedAlpha<dim>::dynamic_terms(
      const contact::ContactProblem<dim> &contact,
      const StepInput                    &in,
      const Vector                       &uh) const
    {
      const double dt = in.dt;
      Vector       vt(in.v), vd(in.v);
      const double c = g / (b * dt);
      vt.add(dt * (1. - g), in.a, -c, uh);
      // Damping velocity of the alpha-weighted equation.
      vd.sadd(af, 1. - af, vt);
      elasticity::DynamicTerms terms;
      const double             m = (1. - am) / (b * dt * dt);
      terms.mass                 = m + (1. - af) * c * aR;
      terms.stiffness            = (1. - af) * (1. + c * bR);
      Vector wM(uh), wK(in.u);
      wM *= m;
      wM.add(-am, in.a, -aR, vd);
      wK *= -af;
      wK.add(-bR, vd);
      terms.mass_load      = ghosted(contact, wM);
      terms.stiffness_load = ghosted(contact, wK);
      return terms;
    }



    template <int dim>
    StepOutcome
    GeneralizedAlpha<dim>::step(contact::ContactProblem<dim> &contact,
                                const StepInput              &in) const
    {
      const double dt = in.dt;
      // u_{n+1} = uh + b dt^2 a_{n+1}, v_{n+1} = vt + g/(b dt) u_{n+1}.
      Vector uh(in.u);
      uh.add(dt, in.v, dt * dt * (0.5 - b), in.a);
      contact.set_dynamic_terms(dynamic_terms(contact, in, uh));
      StepOutcome out;
      // The load surface's row is the alpha-weighted equation too.
      out.state =
        in.load_control ?
          contact.solve_load((1. - af) * in.value + af * in.applied, in.label) :
          contact.solve_displacement(in.value, in.label);
      out.iterations = out.state.iterations;
      out.u          = owned_copy(contact, contact.displacement());
      out.a          = out.u;
      out.a.add(-1., uh);
      out.a *= 1. / (b * dt * dt);
      out.v = in.v;
      out.v.add(dt * (1. - g), in.a, dt * g, out.a);
      return out;
    }



    template <int dim>
    double
    GeneralizedAlpha<dim>::obstacle_force(const double,
                                          const double new_force) const
    {
      return new_force;
    }



    template <int dim>
    Newmark<dim>::Newmark(const double rayleigh_mass,
                          const double rayleigh_stiffness)
      : GeneralizedAlpha<dim>(AlphaCoefficients(),
                              rayleigh_mass,
                              rayleigh_stiffness)
    {}



    template <int dim>
    double
    Newmark<dim>::obstacle_force(const double old_force,
                                 const double new_force) const
    {
      return 0.5 * (old_force + new_force);
    }



    template class GeneralizedAlpha<2>;
    template class GeneralizedAlpha<3>;
    template class Newmark<2>;
    template class Newmark<3>;
  } // namespace dynamics
} // namespace cycloid

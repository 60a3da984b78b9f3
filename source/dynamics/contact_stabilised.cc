#include <deal.II/base/mpi.h>

#include <cycloid/dynamics/contact_stabilised.h>

#include <algorithm>

namespace cycloid
{
  namespace dynamics
  {
    using Vector = dealii::TrilinosWrappers::MPI::Vector;

    template <int dim>
    ContactStabilised<dim>::ContactStabilised(const double rayleigh_mass,
                                              const double rayleigh_stiffness)
      : aR(rayleigh_mass)
      , bR(rayleigh_stiffness)
    {}



    template <int dim>
    double
    ContactStabilised<dim>::predicted_rotation(
      const contact::ContactProblem<dim> &contact,
      const StepInput                    &in) const
    {
      const auto    &el    = contact.elasticity();
      const auto    &owned = el.locally_owned_dofs();
      const MPI_Comm comm  = el.dof_handler().get_communicator();
      // The load surface stays where the predictor puts it: beta_n +
      // dt dbeta/dt, with dbeta/dt read from the velocity of its DoFs
      // (v = dbeta/dt g there); any other choice would make the
      // projection move it and corrupt its velocity.
      double gv = 0, gg = 0;
      for (const auto &[d, g] : contact.load_pattern())
        if (owned.is_element(d))
          {
            gv += g * in.v[d];
            gg += g * g;
          }
      gv = dealii::Utilities::MPI::sum(gv, comm);
      gg = dealii::Utilities::MPI::sum(gg, comm);
      return in.beta + (gg > 0 ? in.dt * gv / gg : 0.);
    }



    template <int dim>
    contact::ContactState
    ContactStabilised<dim>::project_predictor(
      contact::ContactProblem<dim> &contact,
      const StepInput              &in) const
    {
      // Predictor u_n + dt v_n projected onto the admissible set in the
      // mass norm: min |u - u_pred|_M, u admissible.
      Vector pred(in.u);
      pred.add(in.dt, in.v);
      elasticity::DynamicTerms projection;
      projection.stiffness = 0.;
      projection.mass      = 1.;
      projection.mass_load = ghosted(contact, pred);
      contact.set_dynamic_terms(projection);
      return contact.solve_displacement(predicted_rotation(contact, in),
                                        in.label + " (projection)");
    }



    template <int dim>
    elasticity::DynamicTerms
    ContactStabilised<dim>::trapezoidal_terms(
      const contact::ContactProblem<dim> &contact,
      const StepInput                    &in,
      const Vector                       &tilde) const
    {
      // (4/dt^2 M + 2/dt C + K) u = M (4/dt^2) u~ - K u_n - 2 C v_n
      //                              + (2/dt) C u~ + r.
      const double             dt = in.dt;
      elasticity::DynamicTerms terms;
      terms.mass      = 4. / (dt * dt) + 2. * aR / dt;
      terms.stiffness = 1. + 2. * bR / dt;
      Vector wM(tilde), wK(in.u);
      wM *= terms.mass;
      wM.add(-2. * aR, in.v);
      wK *= -1.;
      wK.add(-2. * bR, in.v);
      wK.add(2. * bR / dt, tilde);
      terms.mass_load      = ghosted(contact, wM);
      terms.stiffness_load = ghosted(contact, wK);
      return terms;
    }



    template <int dim>
    StepOutcome
    ContactStabilised<dim>::step(contact::ContactProblem<dim> &contact,
                                 const StepInput              &in) const
    {
      // The last step's set is closer to this step's than the
      // projection's (the mass-norm projection leaves other nodes
      // touching): measured, it saves an iteration per step.
      const std::set<unsigned int> last = contact.active_set();
      const auto                   p    = project_predictor(contact, in);
      const Vector tilde = owned_copy(contact, contact.displacement());
      contact.restart_active_set(last);

      contact.set_dynamic_terms(trapezoidal_terms(contact, in, tilde));
      StepOutcome out;
      // The load surface's row of this equation is the sum of its
      // forces at t_n and t_{n+1} (M a_n of the trapezoidal rule keeps
      // the load of t_n; only the contact forces of t_n are dropped).
      out.state = in.load_control ?
                    contact.solve_load(in.value + in.applied, in.label) :
                    contact.solve_displacement(in.value, in.label);
      out.state.reaction -= in.applied;
      // Likewise the multipliers of the contact rows are the sum of the
      // contact forces at t_n and t_{n+1} (the projection absorbs the
      // old one): M (v_{n+1} - v_n) = dt/2 (... + lambda). Report the
      // step average lambda/2, the force that carries the impulse.
      contact.scale_reactions(0.5);
      out.iterations = p.iterations + out.state.iterations;
      out.state.linear_iterations += p.linear_iterations;
      out.state.preconditioner_setups += p.preconditioner_setups;
      out.state.cycles_broken += p.cycles_broken;
      out.state.cycle_tension =
        std::max(out.state.cycle_tension, p.cycle_tension);
      out.u = owned_copy(contact, contact.displacement());
      // v_{n+1} = v_n + 2/dt (u_{n+1} - u~); the acceleration is not
      // part of the scheme's state (zero).
      out.v = out.u;
      out.v.add(-1., tilde);
      out.v.sadd(2. / in.dt, 1., in.v);
      out.a.reinit(out.u);
      return out;
    }



    template <int dim>
    double
    ContactStabilised<dim>::obstacle_force(const double,
                                           const double new_force) const
    {
      return new_force;
    }



    template class ContactStabilised<2>;
    template class ContactStabilised<3>;
  } // namespace dynamics
} // namespace cycloid

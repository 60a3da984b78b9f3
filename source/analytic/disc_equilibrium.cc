#include <deal.II/base/exceptions.h>

#include <deal.II/lac/full_matrix.h>

#include <cycloid/analytic/load_distribution.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace cycloid
{
  namespace analytic
  {
    namespace
    {
      /** The 3 x 3 block in (t_x, t_y, theta) of a 3 x 4 derivative. */
      dealii::FullMatrix<double>
      motion_block(const dealii::FullMatrix<double> &derivative)
      {
        dealii::FullMatrix<double> J(3, 3);
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            J(a, b) = derivative(a, b);
        return J;
      }

      /** Force and moment scales of disc @p d's loads: the pins' force
       * and moment sums plus the bearings' resultant. */
      std::pair<double, double>
      load_scales(const std::vector<PinLoad> &pins,
                  const unsigned int          d,
                  const double                bearing_force,
                  const double                bearing_moment)
      {
        double f = bearing_force, m = std::abs(bearing_moment);
        for (const PinLoad &p : pins)
          if (p.contact.disc == d)
            {
              f += p.force;
              m += p.force * std::abs(p.contact.arm);
            }
        return {f, m};
      }
    } // namespace



    DiscEquilibrium::DiscEquilibrium(const PairStiffnessModel     &model,
                                     const support::CrankSupports &supports,
                                     const double                  tolerance,
                                     const unsigned int max_iterations,
                                     const double       floor)
      : model(model)
      , supports(supports)
      , tolerance(std::max(tolerance, 1e-13))
      , max_iterations(max_iterations)
      , floor(floor)
    {}



    std::array<double, 3>
    DiscEquilibrium::residual(const unsigned int          d,
                              const support::DiscMotion  &q,
                              const double                beta,
                              const double                floor_now,
                              std::vector<PinLoad>       &pins,
                              dealii::FullMatrix<double> &derivative) const
    {
      const auto b = supports.resultant(d, q, beta, floor_now);
      derivative   = b.derivative;
      std::array<double, 3> r = b.value;
      for (PinLoad &p : pins)
        {
          if (p.contact.disc != d)
            continue;
          const std::array<double, 3> v{
            {p.contact.normal[0], p.contact.normal[1], p.contact.arm}};
          const double c = std::max(p.contact.clearance, 0.);
          p.approach     = std::max(
            v[0] * q.translation[0] + v[1] * q.translation[1] +
              q.rotation * v[2] - c,
            0.);
          p.force = model.force(p.approach, p.pair);
          p.stiffness =
            p.approach > 0 ? model.stiffness(p.approach, p.pair) : 0.;
          // The pin pushes the disc back along -n, with moment -F l.
          for (unsigned int a = 0; a < 3; ++a)
            {
              r[a] -= p.force * v[a];
              for (unsigned int c2 = 0; c2 < 3; ++c2)
                derivative(a, c2) -= p.stiffness * v[a] * v[c2];
            }
        }
      return r;
    }



    void
    DiscEquilibrium::solve_disc(const unsigned int    d,
                                const double          beta,
                                std::vector<PinLoad> &pins,
                                support::DiscMotion  &q) const
    {
      dealii::FullMatrix<double> D(3, 4);
      // A moment weighs as a force at the crank circle.
      const double rho   = supports.crank_circle_radius();
      const auto   merit = [rho](const std::array<double, 3> &r) {
        return r[0] * r[0] + r[1] * r[1] + (r[2] / rho) * (r[2] / rho);
      };
      std::array<double, 3> r = residual(d, q, beta, floor, pins, D);
      for (unsigned int it = 0; it < max_iterations; ++it)
        {
          const auto bearing = supports.resultant(d, q, beta, 0.);
          const auto [fs, ms] =
            load_scales(pins,
                        d,
                        std::hypot(bearing.value[0], bearing.value[1]),
                        bearing.value[2]);
          if (std::hypot(r[0], r[1]) <= tolerance * fs &&
              std::abs(r[2]) <= tolerance * ms)
            return;
          dealii::FullMatrix<double> J = motion_block(D);
          J.gauss_jordan();
          std::array<double, 3> dq{{0., 0., 0.}};
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int b = 0; b < 3; ++b)
              dq[a] -= J(a, b) * r[b];
          // Backtrack while the residual grows: the energy is convex, but
          // a roller or pin that opens or closes makes the step too long.
          double              step = 1.;
          support::DiscMotion trial;
          std::array<double, 3> r_trial;
          for (unsigned int k = 0; k < 40; ++k, step *= 0.5)
            {
              trial             = q;
              trial.translation[0] += step * dq[0];
              trial.translation[1] += step * dq[1];
              trial.rotation += step * dq[2];
              r_trial = residual(d, trial, beta, floor, pins, D);
              if (merit(r_trial) < merit(r))
                break;
            }
          const double size = std::hypot(step * dq[0], step * dq[1]) +
                              std::abs(step * dq[2]) * rho;
          q = trial;
          r = r_trial;
          // Round-off: the step no longer moves the disc.
          if (size <= 1e-15 * (q.translation.norm() + std::abs(q.rotation) * rho))
            return;
        }
      std::ostringstream msg;
      msg << "crank bearings: disc " << d
          << " found no equilibrium on its bearings in " << max_iterations
          << " iterations (Analytic/Maximum iterations) at rotation " << beta
          << " rad.";
      AssertThrow(false, dealii::ExcMessage(msg.str()));
    }



    double
    DiscEquilibrium::torque_at(const double                      beta,
                               std::vector<PinLoad>             &pins,
                               std::vector<support::DiscMotion> &motions,
                               double                           &slope) const
    {
      double torque = 0;
      slope         = 0;
      motions.resize(supports.n_discs());
      for (unsigned int d = 0; d < supports.n_discs(); ++d)
        {
          support::DiscMotion &q = motions[d];
          solve_disc(d, beta, pins, q);
          // dq/dbeta = -J^-1 dR/dbeta with the exact (unfloored)
          // stiffness, but for a guard far below round-off.
          dealii::FullMatrix<double> D(3, 4);
          residual(d, q, beta, 1e-12 * floor, pins, D);
          dealii::FullMatrix<double> J = motion_block(D);
          J.gauss_jordan();
          std::array<double, 3> dq{{0., 0., 0.}};
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int b = 0; b < 3; ++b)
              dq[a] -= J(a, b) * D(b, 3);
          for (const PinLoad &p : pins)
            if (p.contact.disc == d)
              {
                const double l = p.contact.arm;
                torque += p.force * l;
                slope += p.stiffness * l *
                         (p.contact.normal[0] * dq[0] +
                          p.contact.normal[1] * dq[1] + l * dq[2]);
              }
        }
      return torque;
    }



    LoadState
    LoadDistribution::zero_torque_limit(
      const std::vector<PinLoad>    &pins,
      const int                      side,
      const support::CrankSupports &supports) const
    {
      LoadState state = zero_torque_limit(pins, side);
      if (supports.bearing().size().clearance == 0)
        {
          state.motions.assign(supports.n_discs(), {});
          for (auto &q : state.motions)
            q.rotation = state.rotation;
        }
      else
        {
          // The pins' take-up is a lower bound (the disc in its kinematic
          // place just touches); the bearings' clearance lets the discs
          // give way further. The largest rotation with no torque, by
          // bisection of T(beta) (non-decreasing).
          const DiscEquilibrium eq(model,
                                   supports,
                                   tolerance,
                                   max_iterations,
                                   supports.stiffness_floor(1.));
          std::vector<support::DiscMotion> q;
          double                           slope = 0;
          const auto                       loaded = [&](const double x) {
            q.assign(supports.n_discs(), {});
            for (auto &m : q)
              m.rotation = side * x;
            return side * eq.torque_at(side * x, state.pins, q, slope) > 1e-6;
          };
          double lo = side * state.rotation, step = 1e-6, hi = lo + step;
          while (!loaded(hi))
            {
              lo = hi;
              hi += (step *= 2.);
            }
          for (unsigned int k = 0; k < 60 && hi - lo > 1e-15 * hi; ++k)
            (loaded(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
          state.rotation = state.takeup = side * lo;
          loaded(lo);
          state.motions = q;
        }
      for (unsigned int d = 0; d < supports.n_discs(); ++d)
        for (const auto &b : supports.states(d, state.motions[d], state.rotation))
          state.bearings.push_back(b);
      return state;
    }



    LoadState
    LoadDistribution::solve(const std::vector<PinLoad>    &pins_in,
                            const double                   torque,
                            const double                   beta_guess,
                            const support::CrankSupports &supports) const
    {
      const double sign = torque >= 0 ? 1. : -1.;
      LoadState    state =
        zero_torque_limit(pins_in, static_cast<int>(sign), supports);
      state.torque          = torque;
      state.reaction_torque = 0;
      if (torque == 0)
        return state;
      const double          target = torque * 1e3; // N m -> N mm
      const DiscEquilibrium eq(model,
                               supports,
                               tolerance,
                               max_iterations,
                               supports.stiffness_floor(target));
      std::vector<support::DiscMotion> q = state.motions;
      const auto torque_of = [&](const double beta, double &dg) {
        return eq.torque_at(beta, state.pins, q, dg);
      };
      double       dg = 0;
      const double x  = carrying_rotation(torque_of,
                                         std::abs(target),
                                         sign,
                                         sign * state.takeup,
                                         beta_guess,
                                         dg,
                                         state.iterations);
      const double t        = torque_of(sign * x, dg);
      state.rotation        = sign * x;
      state.reaction_torque = t * 1e-3;
      state.k_tangent       = dg * 1e-3;
      state.motions         = q;
      state.pins_in_contact = 0;
      for (const PinLoad &p : state.pins)
        if (p.force > 0)
          ++state.pins_in_contact;
      state.bearings.clear();
      double work = 0;
      for (unsigned int d = 0; d < supports.n_discs(); ++d)
        {
          for (const auto &b : supports.states(d, q[d], state.rotation))
            state.bearings.push_back(b);
          work += supports.work(d, q[d], state.rotation);
        }
      // Each part's share of the output work T beta, over T.
      state.breakdown.bodies   = 0;
      state.breakdown.bearings = work / t;
      state.breakdown.contacts = state.rotation - state.breakdown.bearings;
      return state;
    }
  } // namespace analytic
} // namespace cycloid

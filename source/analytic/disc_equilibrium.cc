#include <deal.II/base/exceptions.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <cycloid/analytic/load_distribution.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace cycloid
{
  namespace analytic
  {
    namespace
    {
      /** The motions of the unknowns @p x. */
      std::vector<support::DiscMotion>
      motions_of(const dealii::Vector<double> &x)
      {
        std::vector<support::DiscMotion> q((x.size() - 1) / 3);
        for (unsigned int d = 0; d < q.size(); ++d)
          {
            q[d].translation[0] = x(3 * d);
            q[d].translation[1] = x(3 * d + 1);
            q[d].rotation       = x(3 * d + 2);
          }
        return q;
      }
      /** @p rhs := @p A^-1 @p rhs; a matrix singular to LAPACK (a disc
       * free in some direction: a bearing with one roller loaded and its
       * pins open) gets a diagonal of 1e-10 times its largest, then more. */
      void
      guarded_solve(const dealii::FullMatrix<double> &A,
                    dealii::Vector<double>           &rhs)
      {
        double scale = 0;
        for (unsigned int i = 0; i < A.m(); ++i)
          scale = std::max(scale, std::abs(A(i, i)));
        for (double shift = 0;;
             shift        = shift == 0 ? 1e-10 * scale : 100 * shift)
          {
                   dealii::LAPACKFullMatrix<double> L(A.m(), A.n());
                   L = A;
                   for (unsigned int i = 0; i < A.m(); ++i)
              L(i, i) += (A(i, i) < 0 ? -shift : shift);
            try
              {
                       L.compute_lu_factorization();
              }
            catch (const dealii::ExceptionBase &)
              {
                       AssertThrow(shift < scale,
                            dealii::ExcMessage(
                              "crank bearings: the discs' equilibrium is "
                                     "singular (a disc free to move)."));
                       continue;
              }
            L.solve(rhs);
                   return;
          }
      }
    } // namespace



    DiscEquilibrium::DiscEquilibrium(const PairStiffnessModel     &model,
                                     const support::CrankSupports &supports,
                                     const double                  tolerance,
                                     const unsigned int max_iterations)
      : model(model)
      , supports(supports)
      , tolerance(std::max(tolerance, 1e-10))
      , max_iterations(max_iterations)
    {}



    void
    DiscEquilibrium::system(const dealii::Vector<double> &x,
                            const double                  torque,
                            const double                  floor,
                            std::vector<PinLoad>         &pins,
                            dealii::Vector<double>       &r,
                            dealii::FullMatrix<double>   &J) const
    {
      // The open pins get a guard with the bearings' (not in the final
      // tangent, whose bearing guard is far smaller).
      const double       guarded = 1e-6 * supports.stiffness_floor(torque);
      const unsigned int nd      = supports.n_discs();
      const unsigned int tb      = 3 * nd; // the torque row, the beta column
      const double       beta    = x(tb);
      const auto         q       = motions_of(x);
      r.reinit(tb + 1);
      J.reinit(tb + 1, tb + 1);
      for (unsigned int d = 0; d < nd; ++d)
        {
          const auto b = supports.resultant(d, q[d], beta, floor);
          for (unsigned int a = 0; a < 3; ++a)
            {
              r(3 * d + a) = b.value[a];
              for (unsigned int c = 0; c < 3; ++c)
                J(3 * d + a, 3 * d + c) = b.derivative(a, c);
              J(3 * d + a, tb) = b.derivative(a, 3);
            }
        }
      r(tb) = -torque;
      for (PinLoad &p : pins)
        {
          const unsigned int          d = p.contact.disc;
          const std::array<double, 3> v{
            {p.contact.normal[0], p.contact.normal[1], p.contact.arm}};
          const double c = std::max(p.contact.clearance, 0.);
          p.approach     = std::max(v[0] * x(3 * d) + v[1] * x(3 * d + 1) +
                                  v[2] * x(3 * d + 2) - c,
                                0.);
          p.force        = model.force(p.approach, p.pair);
          p.stiffness =
            p.approach > 0 ? model.stiffness(p.approach, p.pair) : 0.;
          // An open pin on the loaded side, in the Jacobian only, as stiff
          // as a bearing's guard: else, with every pin just touching,
          // nothing in the Jacobian carries the torque.
          const double k =
            p.approach > 0 || floor < guarded || v[2] * torque <= 0 ?
              p.stiffness :
              floor;
          // The pin pushes its disc back along -n, with moment -F l, and
          // its moment carries the torque.
          for (unsigned int a = 0; a < 3; ++a)
            {
              r(3 * d + a) -= p.force * v[a];
              for (unsigned int c2 = 0; c2 < 3; ++c2)
                J(3 * d + a, 3 * d + c2) -= k * v[a] * v[c2];
              J(tb, 3 * d + a) += k * v[2] * v[a];
            }
          r(tb) += p.force * v[2];
        }
    }



    void
    DiscEquilibrium::gradient(const dealii::Vector<double> &x,
                              const double                  torque,
                              const double                  floor,
                              std::vector<PinLoad>         &pins,
                              dealii::Vector<double>       &g,
                              dealii::FullMatrix<double>   &H) const
    {
      const unsigned int         nd = supports.n_discs();
      const unsigned int         tb = 3 * nd;
      dealii::Vector<double>     r;
      dealii::FullMatrix<double> J;
      system(x, torque, floor, pins, r, J);
      g.reinit(tb + 1);
      H.reinit(tb + 1, tb + 1);
      const auto q = motions_of(x);
      for (unsigned int d = 0; d < nd; ++d)
        {
          const auto b = supports.resultant(d, q[d], x(tb), floor);
          for (unsigned int a = 0; a < 3; ++a)
            {
              g(3 * d + a) = -r(3 * d + a);
              for (unsigned int c = 0; c < 3; ++c)
                H(3 * d + a, 3 * d + c) = -J(3 * d + a, 3 * d + c);
              H(3 * d + a, tb) = -b.derivative(a, 3);
              H(tb, 3 * d + a) = b.derivative(2, a);
            }
          g(tb) += b.value[2];
          H(tb, tb) += b.derivative(2, 3);
        }
      g(tb) -= torque;
    }



    double
    DiscEquilibrium::energy(const dealii::Vector<double> &x,
                            const double                  torque,
                            const std::vector<PinLoad>   &pins) const
    {
      // Gauss-Legendre on [0, a] for each pin's energy (its force law is
      // smooth for a > 0).
      static const double nodes[4]   = {0.0694318442029737,
                                        0.3300094782075719,
                                        0.6699905217924281,
                                        0.9305681557970263};
      static const double weights[4] = {0.1739274225687269,
                                        0.3260725774312731,
                                        0.3260725774312731,
                                        0.1739274225687269};
      const unsigned int  tb         = 3 * supports.n_discs();
      const auto          q          = motions_of(x);
      double              e          = -torque * x(tb);
      for (unsigned int d = 0; d < q.size(); ++d)
        e += supports.energy(d, q[d], x(tb));
      for (const PinLoad &p : pins)
        {
          const unsigned int d = p.contact.disc;
          const double       a = p.contact.normal[0] * x(3 * d) +
                           p.contact.normal[1] * x(3 * d + 1) +
                           p.contact.arm * x(3 * d + 2) -
                           std::max(p.contact.clearance, 0.);
          if (a <= 0)
            continue;
          for (unsigned int k = 0; k < 4; ++k)
            e += weights[k] * a * model.force(nodes[k] * a, p.pair);
        }
      return e;
    }



    double
    DiscEquilibrium::merit(const dealii::Vector<double> &r) const
    {
      const double rho = supports.crank_circle_radius();
      double       m   = 0;
      for (unsigned int k = 0; k < r.size(); ++k)
        m += (k % 3 == 0 && k + 1 < r.size()) || k % 3 == 1 ?
               r(k) * r(k) :
               (r(k) / rho) * (r(k) / rho);
      return m;
    }



    double
    DiscEquilibrium::relative_residual(const dealii::Vector<double> &r,
                                       const double                  torque,
                                       const std::vector<PinLoad>   &pins) const
    {
      // Each disc's force and moment against the largest pin force and
      // moment of the stage (a disc may carry nothing: at a small torque
      // on clearances, one disc can float while the other carries), the
      // torque against itself.
      const unsigned int tb = 3 * supports.n_discs();
      double             fs = 0, ms = 0;
      for (const PinLoad &p : pins)
        {
          fs = std::max(fs, p.force);
          ms = std::max(ms, p.force * std::abs(p.contact.arm));
        }
      double worst = std::abs(r(tb)) / std::abs(torque);
      for (unsigned int d = 0; d < supports.n_discs(); ++d)
        worst = std::max({worst,
                          std::hypot(r(3 * d), r(3 * d + 1)) / fs,
                          std::abs(r(3 * d + 2)) / ms});
      return worst;
    }



    bool
    DiscEquilibrium::newton_step(dealii::Vector<double>       &x,
                                 const double                  torque,
                                 const double                  floor,
                                 std::vector<PinLoad>         &pins,
                                 const dealii::Vector<double> &r) const
    {
      // Newton on the energy (convex: pins and rollers are springs of
      // non-decreasing force, minus the torque's work), its Hessian the
      // system's Jacobian with the torque row taken from the bearings'
      // moments (equal to the pins' at equilibrium), which makes it
      // symmetric. An Armijo line search on the energy then cannot stall
      // where a pin or roller opens or closes.
      dealii::Vector<double>     g, r_trial;
      dealii::FullMatrix<double> H, J_trial;
      gradient(x, torque, floor, pins, g, H);
      dealii::Vector<double> dx(g);
      guarded_solve(H, dx);
      dx *= -1.;
      const double e0    = energy(x, torque, pins);
      const double slope = g * dx;
      double       step  = 1.;
      for (unsigned int k = 0; k < 50; ++k, step *= 0.5)
        {
          dealii::Vector<double> trial(x);
          trial.add(step, dx);
          // Near the minimum the energy's change is below its round-off:
          // then a smaller residual decides.
          if (energy(trial, torque, pins) <= e0 + 1e-4 * step * slope ||
              (system(trial, torque, floor, pins, r_trial, J_trial),
               merit(r_trial) < merit(r)))
            {
              const bool moved = !(trial == x);
              x                = trial;
              return moved;
            }
        }
      return false;
    }



    double
    DiscEquilibrium::tangent(const dealii::Vector<double> &x,
                             const double                  torque,
                             const double                  floor,
                             std::vector<PinLoad>         &pins) const
    {
      // The discs' equilibrium differentiated in beta, with the exact
      // stiffness (open pins none, a bearing with no roller loaded a guard
      // far below round-off).
      const unsigned int         tb = 3 * supports.n_discs();
      dealii::Vector<double>     r;
      dealii::FullMatrix<double> J, K(tb, tb);
      system(x, torque, 1e-12 * floor, pins, r, J);
      dealii::Vector<double> dq(tb);
      for (unsigned int a = 0; a < tb; ++a)
        {
          for (unsigned int b = 0; b < tb; ++b)
            K(a, b) = J(a, b);
          dq(a) = -J(a, tb);
        }
      guarded_solve(K, dq);
      double slope = 0;
      for (unsigned int a = 0; a < tb; ++a)
        slope += J(tb, a) * dq(a);
      return slope;
    }



    DiscEquilibrium::Solution
    DiscEquilibrium::solve(const double                            torque,
                           const double                            beta_guess,
                           const std::vector<support::DiscMotion> &start,
                           std::vector<PinLoad>                   &pins) const
    {
      const unsigned int     nd    = supports.n_discs();
      const unsigned int     tb    = 3 * nd;
      const double           floor = supports.stiffness_floor(torque);
      dealii::Vector<double> x(tb + 1), r;
      for (unsigned int d = 0; d < nd; ++d)
        {
          x(3 * d)     = start.empty() ? 0. : start[d].translation[0];
          x(3 * d + 1) = start.empty() ? 0. : start[d].translation[1];
          x(3 * d + 2) = start.empty() ? beta_guess : start[d].rotation;
        }
      x(tb) = beta_guess;
      dealii::FullMatrix<double> J;
      system(x, torque, floor, pins, r, J);
      Solution s;
      bool     converged = false;
      double   previous  = std::numeric_limits<double>::max();
      for (; s.iterations < max_iterations; ++s.iterations)
        {
          // Done, or no better than the last step where round-off rules
          // (at a vanishing torque, the approaches are a few 1e-12 mm on
          // positions of 1e-3 mm).
          const double now = relative_residual(r, torque, pins);
          if ((converged =
                 now <= tolerance || (now >= 0.5 * previous && now <= 1e-6)))
            break;
          previous = now;
          // Round-off: the energy cannot tell a step from none, so the
          // residual is as small as it gets.
          if (!newton_step(x, torque, floor, pins, r))
            {
              system(x, torque, floor, pins, r, J);
              converged = relative_residual(r, torque, pins) <= 1e-6;
              break;
            }
          system(x, torque, floor, pins, r, J);
        }
      AssertThrow(converged,
                  dealii::ExcMessage(
                    "crank bearings: the discs found no equilibrium on "
                    "their bearings in " +
                    std::to_string(max_iterations) +
                    " iterations (Analytic/Maximum iterations)."));
      s.slope = tangent(x, torque, floor, pins);
      system(x, torque, floor, pins, r, J);
      s.rotation = x(tb);
      s.motions  = motions_of(x);
      return s;
    }



    namespace
    {
      /** The rotation and motions of the limit T -> 0 from solution @p s
       * at torque @p torque [N mm]: the torque divided by ten until it is
       * 1e-3 N mm (1e-6 N m), each solve from the last. There a roller
       * carries some 1e-5 N and is compressed by some 1e-9 mm, so the
       * last is the take-up to about 1e-7 of it; and no solve starts from
       * discs floating in their clearances, where the iteration would
       * stall. */
      DiscEquilibrium::Solution
      vanishing_torque(const DiscEquilibrium    &eq,
                       DiscEquilibrium::Solution s,
                       double                    torque,
                       std::vector<PinLoad>      pins)
      {
        while (std::abs(torque) > 1.0001e-3)
          {
            torque *= 0.1;
            s = eq.solve(torque, s.rotation, s.motions, pins);
          }
        return s;
      }
    } // namespace



    LoadState
    LoadDistribution::zero_torque_limit(
      const std::vector<PinLoad>   &pins,
      const int                     side,
      const support::CrankSupports &supports) const
    {
      LoadState state = zero_torque_limit(pins, side);
      state.motions.assign(supports.n_discs(), {});
      for (auto &q : state.motions)
        q.rotation = state.rotation;
      if (supports.bearing().size().clearance > 0)
        {
          // The pins' take-up is where the discs in their kinematic place
          // touch; the bearings' clearance lets them give way further: the
          // limit from 1 N m down.
          const double          T = side * 1e3;
          const DiscEquilibrium eq(model, supports, tolerance, max_iterations);
          std::vector<PinLoad>  loaded = pins;
          const double          rigid =
            LoadDistribution::solve(pins, side * 1., 0.).rotation;
          const auto s =
            vanishing_torque(eq, eq.solve(T, rigid, {}, loaded), T, pins);
          state.rotation = state.takeup = s.rotation;
          state.motions                 = s.motions;
        }
      for (unsigned int d = 0; d < supports.n_discs(); ++d)
        for (const auto &b :
             supports.states(d, state.motions[d], state.rotation))
          state.bearings.push_back(b);
      return state;
    }



    LoadState
    LoadDistribution::solve(const std::vector<PinLoad>   &pins_in,
                            const double                  torque,
                            const double                  beta_guess,
                            const support::CrankSupports &supports) const
    {
      if (torque == 0)
        return zero_torque_limit(pins_in, 1, supports);
      const double sign = torque >= 0 ? 1. : -1.;
      // Start from the rigid stage's rotation (the bearings only add to
      // it) unless a larger guess is given.
      LoadState    state = LoadDistribution::solve(pins_in, torque, 0.);
      const double start =
        sign * beta_guess > sign * state.rotation ? beta_guess : state.rotation;
      const DiscEquilibrium eq(model, supports, tolerance, max_iterations);
      const auto            s = eq.solve(torque * 1e3, start, {}, state.pins);
      if (supports.bearing().size().clearance > 0)
        state.takeup = vanishing_torque(eq, s, torque * 1e3, pins_in).rotation;
      state.rotation        = s.rotation;
      state.k_tangent       = s.slope * 1e-3;
      state.iterations      = s.iterations;
      state.motions         = s.motions;
      state.pins_in_contact = 0;
      double t              = 0;
      for (const PinLoad &p : state.pins)
        {
          t += p.force * p.contact.arm;
          if (p.force > 0)
            ++state.pins_in_contact;
        }
      state.reaction_torque = t * 1e-3;
      double work           = 0;
      for (unsigned int d = 0; d < supports.n_discs(); ++d)
        {
          for (const auto &b : supports.states(d, s.motions[d], s.rotation))
            state.bearings.push_back(b);
          work += supports.work(d, s.motions[d], s.rotation);
        }
      // Each part's share of the output work T beta, over T.
      state.breakdown.bodies   = 0;
      state.breakdown.bearings = work / t;
      state.breakdown.contacts = state.rotation - state.breakdown.bearings;
      return state;
    }
  } // namespace analytic
} // namespace cycloid

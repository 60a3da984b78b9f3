#include <deal.II/base/exceptions.h>

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <cycloid/reduced/load_distribution.h>

#include <algorithm>
#include <cmath>

namespace cycloid
{
  namespace reduced
  {
    // The load distribution of the reduced model on crank bearings
    // (doc/bearings.md): the unknowns of load_distribution.cc's problem
    // plus each disc's translation and rotation against its bearings.

    void
    ComplementaritySolver::set_supports(const support::CrankSupports &s)
    {
      supports = std::make_unique<support::CrankSupports>(s);
    }



    void
    ComplementaritySolver::supported_system(
      const std::vector<unsigned int>        &active,
      const std::vector<double>              &F,
      const std::vector<support::DiscMotion> &q,
      const double                            beta,
      const double                            torque,
      const double                            floor,
      const double                            bearing_floor,
      dealii::Vector<double>                 &r,
      dealii::FullMatrix<double>             &J) const
    {
      const unsigned int m  = active.size();
      const unsigned int nd = supports->n_discs();
      const unsigned int N  = m + 3 * nd + 1;
      const unsigned int tb = N - 1; // the torque row, the beta column
      r.reinit(N);
      J.reinit(N, N);
      for (unsigned int d = 0; d < nd; ++d)
        {
          const auto b = supports->resultant(d, q[d], beta, bearing_floor);
          for (unsigned int a = 0; a < 3; ++a)
            {
              r(m + 3 * d + a) = b.value[a];
              for (unsigned int c = 0; c < 3; ++c)
                J(m + 3 * d + a, m + 3 * d + c) = b.derivative(a, c);
              J(m + 3 * d + a, tb) = b.derivative(a, 3);
            }
        }
      for (unsigned int a = 0; a < m; ++a)
        {
          const unsigned int i     = active[a];
          const unsigned int d     = pairs[i].disc;
          const unsigned int row   = m + 3 * d;
          const double       theta = q[d].rotation;
          const auto         n     = pairs[i].normal;
          const auto [gap, arm]    = rigid_gap(i, theta);
          const double dl          = arm_slope(i, theta);
          // Gap: the rigid gap at theta, closed by n . t, opened by the
          // bodies' and the near field's give.
          r(a) = gap - n * q[d].translation + approach(i, F[i], floor);
          for (unsigned int b = 0; b < m; ++b)
            {
              r(a) += C(i, active[b]) * F[active[b]];
              J(a, b) = C(i, active[b]);
            }
          J(a, a) += slope(i, F[i], floor);
          J(a, row)     = -n[0];
          J(a, row + 1) = -n[1];
          J(a, row + 2) = -arm;
          // The pin pushes its disc back along -n with moment -F l.
          r(row) -= F[i] * n[0];
          r(row + 1) -= F[i] * n[1];
          r(row + 2) -= F[i] * arm;
          J(row, a)     = -n[0];
          J(row + 1, a) = -n[1];
          J(row + 2, a) = -arm;
          J(row + 2, row + 2) -= F[i] * dl;
          // Torque.
          r(tb) += F[i] * arm;
          J(tb, a) = arm;
          J(tb, row + 2) += F[i] * dl;
        }
      r(tb) -= torque;
    }



    unsigned int
    ComplementaritySolver::supported_newton(
      const std::vector<unsigned int>  &active,
      const double                      torque,
      const double                      floor,
      const double                      bearing_floor,
      std::vector<double>              &F,
      std::vector<support::DiscMotion> &q,
      double                           &beta) const
    {
      const unsigned int m   = active.size();
      const double       rho = supports->crank_circle_radius();
      for (unsigned int it = 1; it <= max_iterations; ++it)
        {
          dealii::Vector<double>     r;
          dealii::FullMatrix<double> Jf;
          supported_system(
            active, F, q, beta, torque, floor, bearing_floor, r, Jf);
          dealii::LAPACKFullMatrix<double> J(r.size(), r.size());
          J = Jf;
          J.compute_lu_factorization();
          J.solve(r);
          double step = 0, scale = 0;
          for (unsigned int a = 0; a < m; ++a)
            {
              F[active[a]] -= r(a);
              step  = std::max(step, std::abs(r(a)));
              scale = std::max(scale, std::abs(F[active[a]]));
            }
          // Every motion measured as a length at the crank circle.
          double move = 0;
          for (unsigned int d = 0; d < q.size(); ++d)
            {
              const unsigned int k = m + 3 * d;
              q[d].translation[0] -= r(k);
              q[d].translation[1] -= r(k + 1);
              q[d].rotation -= r(k + 2);
              move = std::max({move,
                               std::abs(r(k)),
                               std::abs(r(k + 1)),
                               std::abs(r(k + 2)) * rho});
            }
          beta -= r(r.size() - 1);
          if (step <= tolerance * scale &&
              std::abs(r(r.size() - 1)) <= tolerance * std::abs(beta) &&
              move <= tolerance * std::abs(beta) * rho)
            return it;
        }
      AssertThrow(false,
                  dealii::ExcMessage(
                    "reduced model: the Newton iteration of the load "
                    "distribution on crank bearings did not converge in " +
                    std::to_string(max_iterations) +
                    " iterations (Analytic/Maximum iterations)."));
      return max_iterations;
    }



    std::vector<unsigned int>
    ComplementaritySolver::next_supported_set(
      const std::vector<unsigned int>        &active,
      const std::vector<double>              &F,
      const std::vector<support::DiscMotion> &q) const
    {
      return next_set(active, F, [&](const unsigned int i) {
        const unsigned int d = pairs[i].disc;
        return rigid_gap(i, q[d].rotation).first -
               pairs[i].normal * q[d].translation;
      });
    }



    std::vector<support::DiscMotion>
    ComplementaritySolver::initial_motions(const double torque,
                                           const double beta_guess,
                                           const double bearing_floor) const
    {
      // The first set's starting forces (as active_set_loop() takes them),
      // and each disc placed where its bearings alone carry their
      // resultant: the Newton iteration then starts with the bearings
      // loaded as they will be, not from rest.
      const std::vector<unsigned int> active =
        first_active_set(torque, beta_guess);
      const std::vector<double> F = starting_forces(active, torque, beta_guess);
      const unsigned int        nd = supports->n_discs();
      std::vector<std::array<double, 3>> load(nd, {{0., 0., 0.}});
      for (const unsigned int i : active)
        {
          load[pairs[i].disc][0] += F[i] * pairs[i].normal[0];
          load[pairs[i].disc][1] += F[i] * pairs[i].normal[1];
          load[pairs[i].disc][2] += F[i] * rigid_gap(i, beta_guess).second;
        }
      std::vector<support::DiscMotion> q(nd);
      for (unsigned int d = 0; d < nd; ++d)
        {
          q[d].rotation = beta_guess;
          // Newton on the bearings' resultant; a few steps suffice for a
          // start (the rollers' law is a power 1.11 of the approach).
          for (unsigned int it = 0; it < 8; ++it)
            {
              const auto b =
                supports->resultant(d, q[d], beta_guess, bearing_floor);
              dealii::FullMatrix<double> J(3, 3);
              dealii::Vector<double>     r(3), dq(3);
              for (unsigned int a = 0; a < 3; ++a)
                {
                  r(a) = b.value[a] - load[d][a];
                  for (unsigned int c = 0; c < 3; ++c)
                    J(a, c) = b.derivative(a, c);
                }
              J.gauss_jordan();
              J.vmult(dq, r);
              q[d].translation[0] -= dq(0);
              q[d].translation[1] -= dq(1);
              q[d].rotation -= dq(2);
            }
        }
      return q;
    }



    ReducedSolution
    ComplementaritySolver::solve_supported(const double torque,
                                           const double beta_guess) const
    {
      const unsigned int n  = pairs.size();
      const unsigned int nd = supports->n_discs();
      ReducedSolution    s;
      s.force.assign(n, 0.);
      s.compliance.assign(n, 0.);
      s.rotation = beta_guess;
      s.motions.assign(nd, {});
      for (auto &q : s.motions)
        q.rotation = beta_guess;
      if (torque == 0 || n == 0)
        return s;
      const double floor         = force_floor(torque);
      const double bearing_floor = supports->stiffness_floor(torque);
      s.motions = initial_motions(torque, beta_guess, bearing_floor);
      std::vector<double> F;
      const auto          active = active_set_loop(
        torque,
        beta_guess,
        floor,
        [&](const std::vector<unsigned int> &set, std::vector<double> &f) {
          return supported_newton(
            set, torque, floor, bearing_floor, f, s.motions, s.rotation);
        },
        [&](const std::vector<unsigned int> &set,
            const std::vector<double>       &f) {
          return next_supported_set(set, f, s.motions);
        },
        F,
        s);

      // dT/dbeta: the system without the torque row, differentiated in
      // beta, with the exact (unguarded) bearing stiffness.
      dealii::Vector<double>     r;
      dealii::FullMatrix<double> Jf;
      supported_system(active,
                       F,
                       s.motions,
                       s.rotation,
                       torque,
                       floor,
                       1e-12 * bearing_floor,
                       r,
                       Jf);
      const unsigned int               N = r.size() - 1;
      dealii::LAPACKFullMatrix<double> J(N, N);
      dealii::Vector<double>           x(N);
      for (unsigned int a = 0; a < N; ++a)
        {
          for (unsigned int b = 0; b < N; ++b)
            J(a, b) = Jf(a, b);
          x(a) = -Jf(a, N);
        }
      J.compute_lu_factorization();
      J.solve(x);
      s.k_tangent = 0;
      for (unsigned int a = 0; a < N; ++a)
        s.k_tangent += Jf(N, a) * x(a);

      set_forces(F, floor, s);
      for (unsigned int d = 0; d < nd; ++d)
        s.bearings_work += supports->work(d, s.motions[d], s.rotation);
      return s;
    }
  } // namespace reduced
} // namespace cycloid

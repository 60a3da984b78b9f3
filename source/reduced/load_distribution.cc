#include <deal.II/base/exceptions.h>

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <cycloid/reduced/load_distribution.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace cycloid
{
  namespace reduced
  {
    ComplementaritySolver::ComplementaritySolver(
      const dealii::FullMatrix<double> &compliance,
      const std::vector<ContactPair>   &pairs,
      const double                      tolerance,
      const unsigned int                max_iterations)
      : C(compliance)
      , pairs(pairs)
      , tolerance(tolerance)
      , max_iterations(max_iterations)
    {
      AssertThrow(C.m() == pairs.size() && C.n() == pairs.size(),
                  dealii::ExcInternalError());
    }



    std::pair<double, double>
    ComplementaritySolver::rigid_gap(const unsigned int i,
                                     const double       beta) const
    {
      const ContactPair &p = pairs[i];
      if (p.rigid_gap)
        return p.rigid_gap(beta);
      return {p.clearance - beta * p.arm, p.arm};
    }



    double
    ComplementaritySolver::arm_slope(const unsigned int i,
                                     const double       beta) const
    {
      if (!pairs[i].rigid_gap)
        return 0.;
      // Central difference over a step small against the rotations of a
      // loaded state (1e-4 rad and more) and large against round-off.
      const double h = 1e-7;
      return (rigid_gap(i, beta + h).second - rigid_gap(i, beta - h).second) /
             (2. * h);
    }



    double
    ComplementaritySolver::approach(const unsigned int i,
                                    const double       force,
                                    const double       floor) const
    {
      const ContactPair &p = pairs[i];
      if (force >= floor)
        return p.law.approach(force / p.length);
      return p.law.approach(floor / p.length) +
             slope(i, floor, floor) * (force - floor);
    }



    double
    ComplementaritySolver::slope(const unsigned int i,
                                 const double       force,
                                 const double       floor) const
    {
      const ContactPair &p = pairs[i];
      return p.law.slope(std::max(force, floor) / p.length) / p.length;
    }



    unsigned int
    ComplementaritySolver::newton(const std::vector<unsigned int> &active,
                                  const double                     torque,
                                  const double                     floor,
                                  std::vector<double>             &F,
                                  double                          &beta) const
    {
      const unsigned int m = active.size();
      for (unsigned int it = 1; it <= max_iterations; ++it)
        {
          // Residual: gap of each active contact, then the torque balance.
          dealii::Vector<double>           r(m + 1);
          dealii::LAPACKFullMatrix<double> J(m + 1, m + 1);
          for (unsigned int a = 0; a < m; ++a)
            {
              const unsigned int i  = active[a];
              const auto [gap, arm] = rigid_gap(i, beta);
              r(a)                  = gap + approach(i, F[i], floor);
              for (unsigned int b = 0; b < m; ++b)
                {
                  r(a) += C(i, active[b]) * F[active[b]];
                  J(a, b) = C(i, active[b]);
                }
              J(a, a) += slope(i, F[i], floor);
              J(a, m) = -arm;
              J(m, a) = arm;
              J(m, m) += F[i] * arm_slope(i, beta);
              r(m) += arm * F[i];
            }
          r(m) -= torque;
          J.compute_lu_factorization();
          J.solve(r);
          double step = 0, scale = 0;
          for (unsigned int a = 0; a < m; ++a)
            {
              F[active[a]] -= r(a);
              step  = std::max(step, std::abs(r(a)));
              scale = std::max(scale, std::abs(F[active[a]]));
            }
          beta -= r(m);
          if (step <= tolerance * scale &&
              std::abs(r(m)) <= tolerance * std::abs(beta))
            return it;
        }
      AssertThrow(false,
                  dealii::ExcMessage(
                    "reduced model: the Newton iteration of the load "
                    "distribution did not converge in " +
                    std::to_string(max_iterations) +
                    " iterations (Analytic/Maximum iterations)."));
      return max_iterations;
    }



    std::vector<unsigned int>
    ComplementaritySolver::first_active_set(const double torque,
                                            const double beta_guess) const
    {
      const unsigned int        n = pairs.size();
      std::vector<unsigned int> active;
      for (unsigned int i = 0; i < n; ++i)
        if (rigid_gap(i, beta_guess).first < 0 && beta_guess * torque > 0)
          active.push_back(i);
      if (!active.empty())
        return active;
      // The contact with the smallest clearance per arm on the loaded side
      // closes first.
      unsigned int best = n;
      for (unsigned int i = 0; i < n; ++i)
        if (pairs[i].arm * torque > 0 &&
            (best == n || pairs[i].clearance / std::abs(pairs[i].arm) <
                            pairs[best].clearance / std::abs(pairs[best].arm)))
          best = i;
      AssertThrow(best < n,
                  dealii::ExcMessage("reduced model: no contact can "
                                     "carry a torque of this sign."));
      return {best};
    }



    std::vector<unsigned int>
    ComplementaritySolver::next_active_set(
      const std::vector<unsigned int> &active,
      const std::vector<double>       &F,
      const double                     beta) const
    {
      return next_set(active, F, [&](const unsigned int i) {
        return rigid_gap(i, beta).first;
      });
    }



    std::vector<unsigned int>
    ComplementaritySolver::next_set(
      const std::vector<unsigned int>           &active,
      const std::vector<double>                 &F,
      const std::function<double(unsigned int)> &rigid_gap_of) const
    {
      const unsigned int        n = pairs.size();
      std::vector<unsigned int> next;
      std::vector<bool>         is_active(n, false);
      for (const unsigned int i : active)
        is_active[i] = true;
      for (unsigned int i = 0; i < n; ++i)
        {
          if (is_active[i])
            {
              if (F[i] > 0)
                next.push_back(i);
              continue;
            }
          double gap = rigid_gap_of(i);
          for (const unsigned int j : active)
            gap += C(i, j) * F[j];
          if (gap < 0)
            next.push_back(i);
        }
      return next;
    }



    double
    ComplementaritySolver::tangent_stiffness(
      const std::vector<unsigned int> &active,
      const std::vector<double>       &F,
      const double                     floor,
      const double                     beta) const
    {
      const unsigned int               m = active.size();
      dealii::LAPACKFullMatrix<double> J(m, m);
      dealii::Vector<double>           l(m), x(m);
      for (unsigned int a = 0; a < m; ++a)
        {
          for (unsigned int b = 0; b < m; ++b)
            J(a, b) = C(active[a], active[b]);
          J(a, a) += slope(active[a], F[active[a]], floor);
          l(a) = rigid_gap(active[a], beta).second;
        }
      J.compute_lu_factorization();
      x = l;
      J.solve(x);
      double k = l * x;
      for (const unsigned int i : active)
        k += F[i] * arm_slope(i, beta);
      return k;
    }



    std::vector<unsigned int>
    ComplementaritySolver::active_set_loop(
      const double                                              torque,
      const double                                              beta_guess,
      const double                                              floor,
      const std::function<unsigned int(const std::vector<unsigned int> &,
                                       std::vector<double> &)> &newton_on,
      const std::function<
        std::vector<unsigned int>(const std::vector<unsigned int> &,
                                  const std::vector<double> &)> &next_of,
      std::vector<double>                                       &F,
      ReducedSolution                                           &s) const
    {
      const unsigned int        n      = pairs.size();
      std::vector<unsigned int> active = first_active_set(torque, beta_guess);
      std::set<std::vector<unsigned int>> seen;
      F = starting_forces(active, torque, beta_guess);
      while (true)
        {
          AssertThrow(seen.insert(active).second,
                      dealii::ExcMessage(
                        "reduced model: the active set of the load "
                        "distribution cycles (a set repeated after " +
                        std::to_string(seen.size()) + " sets)."));
          s.iterations += newton_on(active, F);
          ++s.active_sets;
          const std::vector<unsigned int> next = next_of(active, F);
          if (next == active)
            break;
          for (unsigned int i = 0; i < n; ++i)
            if (!std::binary_search(next.begin(), next.end(), i))
              F[i] = 0;
            else if (F[i] <= 0)
              F[i] = floor;
          active = next;
          AssertThrow(!active.empty(),
                      dealii::ExcMessage("reduced model: every contact left "
                                         "the active set."));
        }
      return active;
    }



    std::vector<double>
    ComplementaritySolver::starting_forces(
      const std::vector<unsigned int> &active,
      const double                     torque,
      const double                     beta_guess) const
    {
      // One force on every active contact that carries the torque (not
      // T / (n l_i): a contact at the root has l_i ~ 0).
      std::vector<double> F(pairs.size(), 0.);
      double              active_arms = 0;
      for (const unsigned int i : active)
        active_arms += rigid_gap(i, beta_guess).second;
      for (const unsigned int i : active)
        F[i] = torque / active_arms;
      return F;
    }



    void
    ComplementaritySolver::set_forces(const std::vector<double> &F,
                                      const double               floor,
                                      ReducedSolution           &s) const
    {
      for (unsigned int i = 0; i < pairs.size(); ++i)
        {
          s.force[i] = std::max(F[i], 0.);
          s.compliance[i] =
            C(i, i) + (s.force[i] > 0 ? slope(i, s.force[i], floor) : 0.);
        }
      s.bodies_work = C.matrix_norm_square(
        dealii::Vector<double>(s.force.begin(), s.force.end()));
    }



    double
    ComplementaritySolver::force_floor(const double torque) const
    {
      double arms = 0;
      for (const ContactPair &p : pairs)
        arms += std::abs(p.arm);
      return 1e-9 * std::abs(torque) / arms;
    }



    ReducedSolution
    ComplementaritySolver::solve(const double torque,
                                 const double beta_guess) const
    {
      if (supports)
        return solve_supported(torque, beta_guess);
      const unsigned int n = pairs.size();
      ReducedSolution    s;
      s.force.assign(n, 0.);
      s.compliance.assign(n, 0.);
      s.rotation = beta_guess;
      if (torque == 0 || n == 0)
        return s;
      const double        floor = force_floor(torque);
      std::vector<double> F;
      const auto          active = active_set_loop(
        torque,
        beta_guess,
        floor,
        [&](const std::vector<unsigned int> &set, std::vector<double> &f) {
          return newton(set, torque, floor, f, s.rotation);
        },
        [&](const std::vector<unsigned int> &set,
            const std::vector<double>       &f) {
          return next_active_set(set, f, s.rotation);
        },
        F,
        s);
      s.k_tangent = tangent_stiffness(active, F, floor, s.rotation);
      set_forces(F, floor, s);
      return s;
    }
  } // namespace reduced
} // namespace cycloid

// Tests of the reduced model's parts that need no mesh: the near-field law
// against the half-space solution computed independently (the Flamant log
// kernel integrated numerically), the closed form of the axis approach
// against the integrated Hertz stresses, and the complementarity solver's
// conditions, torque balance and tangent.

#include <deal.II/base/numbers.h>

#include <deal.II/lac/full_matrix.h>

#include <cycloid/reduced/load_distribution.h>
#include <cycloid/reduced/local_contact.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace cycloid;
using namespace cycloid::reduced;

namespace
{
  constexpr double pi = dealii::numbers::PI;

  /**
   * Surface displacement of a plane-strain half-space (compliance c =
   * (1-nu^2)/E) under a semi-elliptic pressure of half-width @p a and line
   * load @p q, up to the common constant of the Flamant solution:
   * u(x) = -(2c/pi) int p(s) ln|x - s| ds, by the midpoint rule in
   * s = a sin(t) (p ds ~ cos^2 t dt is smooth; the log singularity is
   * integrable).
   */
  double
  flamant_displacement(const double       x,
                       const double       a,
                       const double       q,
                       const double       c,
                       const unsigned int n = 4000)
  {
    double sum = 0;
    for (unsigned int k = 0; k < n; ++k)
      {
        const double t  = -pi / 2 + pi * (k + 0.5) / n;
        const double p  = 2. * q / (pi * a) * std::cos(t); // p(s)
        const double ds = a * std::cos(t) * pi / n;
        sum += p * std::log(std::abs(x - a * std::sin(t)) + 1e-300) * ds;
      }
    return -2. * c / pi * sum;
  }
} // namespace



TEST(ReducedLocalContact, MatchesTheHalfSpaceFromTheFlamantKernel)
{
  // The law's claim: the centre approach of the Hertz pressure (half-width
  // a(q)) minus the pressure-weighted mean displacement of a semi-elliptic
  // load of half-width w. Both from the log kernel, numerically.
  const double       c = (1 - 0.3 * 0.3) / 212000., w = 0.25, inv_r = 0.2;
  const LocalContact law(w, c, inv_r);
  for (const double q : {10., 150., 600.})
    {
      const double       a      = law.half_width(q);
      const double       centre = flamant_displacement(0, a, q, c);
      double             mean   = 0;
      const unsigned int n      = 400;
      for (unsigned int k = 0; k < n; ++k)
        {
          const double t = -pi / 2 + pi * (k + 0.5) / n;
          // weight p(x) dx / q = (2/pi) cos^2 t dt
          mean += 2. / pi * std::cos(t) * std::cos(t) * pi / n *
                  flamant_displacement(w * std::sin(t), w, q, c);
        }
      const double expected = centre - mean;
      EXPECT_NEAR(law.approach(q), expected, 2e-3 * std::abs(expected))
        << "q = " << q << " N/mm, a = " << a << " mm";
    }
}



TEST(ReducedLocalContact, SlopeIsTheDerivative)
{
  const LocalContact law(0.2, 1e-5, 0.1);
  for (const double q : {1., 50., 800.})
    {
      const double h = 1e-6 * q;
      EXPECT_NEAR(law.slope(q),
                  (law.approach(q + h) - law.approach(q - h)) / (2 * h),
                  1e-6 * std::abs(law.slope(q)));
    }
  EXPECT_EQ(law.approach(0.), 0.);
}



TEST(ReducedLocalContact, AxisApproachIsTheIntegratedHertzStrain)
{
  // Johnson §4.2: on the axis sigma_z = -p0 a / sqrt(a^2 + z^2), sigma_x =
  // -(p0/a)((a^2 + 2 z^2)/sqrt(a^2 + z^2) - 2 z); plane strain eps_z =
  // ((1-nu^2) sigma_z - nu (1+nu) sigma_x) / E, integrated over [0, z].
  const double E = 212000, nu = 0.3, a = 0.08, q = 300;
  const double p0 = 2 * q / (pi * a);
  for (const double depth : {0.05, 0.4, 3.})
    {
      double             sum = 0;
      const unsigned int n   = 20000;
      for (unsigned int k = 0; k < n; ++k)
        {
          const double z  = depth * (k + 0.5) / n;
          const double r  = std::sqrt(a * a + z * z);
          const double sz = -p0 * a / r;
          const double sx = -(p0 / a) * ((a * a + 2 * z * z) / r - 2 * z);
          sum -= ((1 - nu * nu) * sz - nu * (1 + nu) * sx) / E * depth / n;
        }
      EXPECT_NEAR(halfspace_axis_approach(q, a, depth, E, nu), sum, 1e-7 * sum);
    }
}



namespace
{
  /** Three contacts coupled through a full compliance, one far off. */
  std::vector<ContactPair>
  three_pairs()
  {
    std::vector<ContactPair> pairs(3);
    const double             arms[3]       = {80, 85, 60};
    const double             clearances[3] = {0.012, 0.010, 0.5};
    for (unsigned int i = 0; i < 3; ++i)
      {
        pairs[i].arm       = arms[i];
        pairs[i].clearance = clearances[i];
        pairs[i].length    = 16;
        pairs[i].law       = LocalContact(0.25, 2 * 0.91 / 212000., 0.2);
      }
    return pairs;
  }

  dealii::FullMatrix<double>
  coupled_compliance()
  {
    dealii::FullMatrix<double> C(3, 3);
    const double               c[3][3] = {{4e-6, 1e-6, 0.5e-6},
                                          {1e-6, 5e-6, 0.8e-6},
                                          {0.5e-6, 0.8e-6, 3e-6}};
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        C(i, j) = c[i][j];
    return C;
  }
} // namespace



TEST(ReducedLoadDistribution, ComplementarityAndTorqueBalance)
{
  const auto                  pairs = three_pairs();
  const auto                  C     = coupled_compliance();
  const ComplementaritySolver solver(C, pairs, 1e-12, 50);
  const double                T      = 2e5; // N mm
  const ReducedSolution       s      = solver.solve(T, 1e-4);
  double                      torque = 0;
  for (unsigned int i = 0; i < 3; ++i)
    {
      torque += s.force[i] * pairs[i].arm;
      double gap = pairs[i].clearance - s.rotation * pairs[i].arm +
                   pairs[i].law.approach(s.force[i] / pairs[i].length);
      for (unsigned int j = 0; j < 3; ++j)
        gap += C(i, j) * s.force[j];
      EXPECT_GE(s.force[i], 0.);
      EXPECT_GE(gap, -1e-12);
      if (s.force[i] > 0)
        {
          EXPECT_NEAR(gap, 0., 1e-12) << "contact " << i;
        }
    }
  EXPECT_NEAR(torque, T, 1e-9 * T);
  // Contact 2 (0.5 mm clearance) stays open, the other two carry.
  EXPECT_GT(s.force[0], 0.);
  EXPECT_GT(s.force[1], 0.);
  EXPECT_EQ(s.force[2], 0.);
}



TEST(ReducedLoadDistribution, TangentIsTheDerivativeOfTheTorque)
{
  const ComplementaritySolver solver(coupled_compliance(),
                                     three_pairs(),
                                     1e-13,
                                     50);
  const double                T = 2e5, dT = 1e-4 * T;
  const auto                  s = solver.solve(T, 1e-4);
  const double                fd =
    2 * dT /
    (solver.solve(T + dT, 1e-4).rotation - solver.solve(T - dT, 1e-4).rotation);
  EXPECT_NEAR(s.k_tangent, fd, 1e-5 * fd);
}



TEST(ReducedLoadDistribution, ExactSetFromAnyStart)
{
  // The same state from a start that closes every contact and from one
  // that closes none.
  const ComplementaritySolver solver(coupled_compliance(),
                                     three_pairs(),
                                     1e-12,
                                     50);
  const auto a = solver.solve(2e5, 1e-2), b = solver.solve(2e5, 1e-9);
  EXPECT_NEAR(a.rotation, b.rotation, 1e-12 * a.rotation);
  for (unsigned int i = 0; i < 3; ++i)
    EXPECT_NEAR(a.force[i], b.force[i], 1e-8 * a.force[0]);
}

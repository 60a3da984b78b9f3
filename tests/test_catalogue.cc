// Tests of the figures a designer reads: the catalogue torque cycle and the
// rigidity, lost motion and backlash read from its torsion curve (against a
// bilinear curve whose figures are known in closed form), and the Hertz
// subsurface shear stress (against the textbook values of the line contact).

#include <cycloid/analytic/pair_stiffness.h>
#include <cycloid/parameters/loading.h>
#include <cycloid/postprocess/catalogue.h>
#include <cycloid/postprocess/sweep_noise.h>
#include <cycloid/results/stage_state.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace cycloid;

namespace
{
  using Loading = parameters::LoadingParameters;

  /** A cycle of @p steps steps to @p rated N m. */
  std::vector<double>
  cycle(const double rated, const unsigned int steps)
  {
    Loading l;
    l.rated_torque       = rated;
    l.torque_cycle       = true;
    l.torque_cycle_steps = steps;
    return l.load_values();
  }
} // namespace



TEST(TorqueCycle, GoesZeroPlusMinusZeroWithTheCataloguePoints)
{
  const double              rated = 500.;
  const std::vector<double> t     = cycle(rated, 8);
  // Per branch: the zero limit, 3 %, 50 %, 100 %; four branches share
  // their turning points: 4 + 3 + 4 + 3 states.
  ASSERT_EQ(t.size(), 14u);
  EXPECT_EQ(t.front(), 0.);
  EXPECT_EQ(t.back(), 0.);
  // The zero between the branches twice: the end of one, the start of the
  // other, each approached from its own side.
  EXPECT_EQ(t[6], 0.);
  EXPECT_EQ(t[7], 0.);
  EXPECT_EQ(std::count(t.begin(), t.end(), 0.), 4);
  const std::vector<int> side{1, 1, -1, -1};
  unsigned int           k = 0;
  for (unsigned int i = 0; i < t.size(); ++i)
    if (t[i] == 0)
      {
        EXPECT_EQ(Loading::zero_side(t, i), side[k++]) << i;
      }
  EXPECT_DOUBLE_EQ(*std::max_element(t.begin(), t.end()), rated);
  EXPECT_DOUBLE_EQ(*std::min_element(t.begin(), t.end()), -rated);
  EXPECT_EQ(std::count(t.begin(), t.end(), 0.03 * rated), 2);
  EXPECT_EQ(std::count(t.begin(), t.end(), -0.03 * rated), 2);
  // Up to +R, down through zero to -R, up to zero: the sign of each step.
  const std::vector<int> direction{1, 1, 1, -1, -1, -1, 0, -1, -1, -1, 1, 1, 1};
  for (unsigned int i = 0; i + 1 < t.size(); ++i)
    EXPECT_EQ(t[i + 1] > t[i] ? 1 :
              t[i + 1] < t[i] ? -1 :
                                0,
              direction[i])
      << i;
  // The equal steps are kept: 40 steps to 1000 N m hit every 100 N m.
  const std::vector<double> fine = cycle(1000., 40);
  for (unsigned int k = 1; k <= 10; ++k)
    EXPECT_EQ(std::count_if(fine.begin(),
                            fine.end(),
                            [&](double x) {
                              return std::abs(x - 100. * k) < 1e-9;
                            }),
              k == 10 ? 1 : 2)
      << k;
}



TEST(TorqueCycle, CatalogueFiguresOfABilinearCurve)
{
  // theta(T) = sign(T) c + T / K: a clearance c taken up rigidly, then a
  // linear spring K. Rigidity K, backlash 2 c (plus the zero limits'
  // twist), lost motion 2 c + 0.06 R / K, of which 2 c is clearance.
  namespace u                                = results::units;
  const double                           K   = 2.5e6; // N m/rad
  const double                           c   = 4e-5;  // rad
  const double                           R   = 800.;  // N m
  const double                           psi = 0.1;   // rad
  std::vector<postprocess::TorsionPoint> curve;
  const std::vector<double>              loads = cycle(R, 12);
  for (unsigned int i = 0; i < loads.size(); ++i)
    {
      const double T = loads[i];
      const double side =
        T != 0 ? (T > 0 ? 1 : -1) : Loading::zero_side(loads, i);
      curve.push_back({psi, T, side * c + T / K, side * c});
    }
  const auto f =
    postprocess::catalogue_figures(curve, R, Loading::lost_motion_torque);
  EXPECT_NEAR(f.rigidity_Nm_per_arcmin, K * u::rad_per_arcmin, 1e-9 * K);
  EXPECT_NEAR(f.backlash_arcmin, 2 * c * u::arcmin_per_rad, 1e-12);
  EXPECT_NEAR(f.lost_motion_arcmin,
              (2 * c + 0.06 * R / K) * u::arcmin_per_rad,
              1e-12);
  EXPECT_NEAR(f.lost_motion_clearance_arcmin, 2 * c * u::arcmin_per_rad, 1e-12);
  EXPECT_NEAR(f.lost_motion_elastic_arcmin,
              0.06 * R / K * u::arcmin_per_rad,
              1e-12);
  EXPECT_DOUBLE_EQ(f.crank, psi);
  EXPECT_DOUBLE_EQ(f.rated_torque, R);

  // A curve without the +-3 % states cannot give the lost motion.
  std::vector<postprocess::TorsionPoint> gappy;
  for (const auto &p : curve)
    if (std::abs(std::abs(p.torque) - 0.03 * R) > 1e-6)
      gappy.push_back(p);
  EXPECT_THROW(postprocess::catalogue_figures(gappy,
                                              R,
                                              Loading::lost_motion_torque),
               dealii::ExceptionBase);
}



TEST(HertzStress, SubsurfaceShearOfTheLineContact)
{
  // Johnson, Contact Mechanics, sec. 4.2: the principal shear stress of
  // the line contact peaks at 0.300 p0, at a depth of 0.786 a, whatever
  // nu (plane strain: sigma_y lies between sigma_x and sigma_z there).
  for (const double nu : {0.25, 0.3, 0.35})
    {
      const auto s = analytic::hertz_subsurface_shear(nu);
      EXPECT_NEAR(s.stress_ratio, 0.300283, 2e-6) << nu;
      EXPECT_NEAR(s.depth_ratio, 0.786151, 2e-6) << nu;
    }
  // Without sigma_y (nu = 0) the surface, where sigma_x = sigma_z = -p0
  // and sigma_y = 0, carries the largest Tresca stress p0 / 2.
  const auto s0 = analytic::hertz_subsurface_shear(0.);
  EXPECT_NEAR(s0.stress_ratio, 0.5, 1e-9);
  EXPECT_NEAR(s0.depth_ratio, 0., 1e-6);

  // A pin's figures: p0 = 2 F / (pi a b), tau and depth scale with them.
  results::PinState pin;
  pin.fn              = 2000.; // N
  pin.hertz_halfwidth = 0.05;  // mm
  analytic::set_hertz_stresses(pin, 16., 0.3);
  const double p0 = 2 * 2000. / (M_PI * 0.05 * 16.);
  EXPECT_NEAR(pin.hertz_pressure, p0, 1e-9 * p0);
  EXPECT_NEAR(pin.max_shear_stress, 0.300283 * p0, 1e-5 * p0);
  EXPECT_NEAR(pin.max_shear_depth, 0.786151 * 0.05, 1e-7);
}



TEST(SweepNoise, NoiseIsNotResolvedASmoothVariationIs)
{
  // A first harmonic over one closed period, 10 phases: resolved.
  std::vector<double> smooth, noisy;
  for (unsigned int k = 0; k < 10; ++k)
    smooth.push_back(1e7 * (1 + 0.02 * std::sin(2 * M_PI * k / 9.)));
  const auto s = postprocess::sweep_noise(smooth);
  EXPECT_NEAR(s.fluctuation, 0.04 * std::sin(2 * M_PI * 2 / 9.), 1e-12);
  EXPECT_LT(s.closure, 1e-12);
  EXPECT_TRUE(s.resolved) << s.floor;
  // Zero-mean alternating "noise" of the same range: not resolved.
  for (unsigned int k = 0; k < 10; ++k)
    noisy.push_back(1e7 * (1 + 0.02 * ((k * 7) % 3 - 1.)));
  const auto n = postprocess::sweep_noise(noisy);
  EXPECT_FALSE(n.resolved) << n.fluctuation << " " << n.floor;
  EXPECT_GT(n.roughness, n.fluctuation / 2);
  // Three phases whose ends agree to round-off (a periodic mesh): the
  // floor is unknown, and nothing is called resolved.
  const auto u = postprocess::sweep_noise({1e7, 1.05e7, 1e7});
  EXPECT_TRUE(std::isnan(u.floor));
  EXPECT_FALSE(u.resolved);
  // Three phases on different meshes: the closure is the floor.
  const auto c = postprocess::sweep_noise({1e7, 1.05e7, 1.01e7});
  EXPECT_NEAR(c.floor, 0.01, 1e-12);
  EXPECT_TRUE(c.resolved);
}



TEST(SweepNoise, TheChangeSinceACoarserPassReplacesTheRoughness)
{
  // A step as a pin engages between phases 2 and 3 of 5: rough to the
  // second-difference criterion, though physical.
  const std::vector<double> fine = {
    6.147e6, 6.163e6, 6.297e6, 6.304e6, 6.147e6};
  const auto rough = postprocess::sweep_noise(fine);
  EXPECT_FALSE(rough.resolved) << rough.floor;
  EXPECT_TRUE(std::isnan(rough.refinement));
  // The same curve one level coarser, shifted by the same 6210 N m/rad
  // everywhere (moves no fluctuation) and 0.05 % of 6.21e6 lower at
  // phase 3.
  std::vector<double> coarser;
  for (const double k : fine)
    coarser.push_back(k + 0.001 * 6.21e6);
  coarser[2] -= 0.0005 * 6.21e6;
  const auto n    = postprocess::sweep_noise(fine, coarser);
  double     mean = 0, shift = 0;
  for (unsigned int i = 0; i < fine.size(); ++i)
    {
      mean += fine[i] / fine.size();
      shift += (fine[i] - coarser[i]) / fine.size();
    }
  double change = 0;
  for (unsigned int i = 0; i < fine.size(); ++i)
    change = std::max(change, std::abs(fine[i] - coarser[i] - shift) / mean);
  EXPECT_NEAR(n.refinement, change, 1e-15);
  // The bump less its share of the shift: 4/5 of 0.05 % at phase 3.
  EXPECT_NEAR(n.refinement, 0.0004 * 6.21e6 / mean, 1e-12);
  EXPECT_DOUBLE_EQ(n.floor, std::max(n.closure, n.refinement));
  EXPECT_TRUE(n.resolved) << n.floor << " " << n.fluctuation;
  // A coarser pass whose phase 3 differs by the whole range (4/5 of it
  // after the shift, more than half the fluctuation): the floor follows,
  // not resolved.
  std::vector<double> moved = fine;
  moved[2] -= 6.304e6 - 6.147e6;
  EXPECT_FALSE(postprocess::sweep_noise(fine, moved).resolved);
  // A coarser pass of another length is no coarser pass.
  EXPECT_TRUE(std::isnan(postprocess::sweep_noise(fine, {1., 2.}).refinement));
}

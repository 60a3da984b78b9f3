// Tests of the crank bearings (issue #52): the needle bearing's roller law
// against Palmgren's formula and its load share against Stribeck's closed
// form, and the analytic and reduced models on bearings against what the
// mechanics says must hold: each disc in equilibrium of force and moment,
// the bearings' moments carrying the output torque, the output work split
// exactly into the parts of compliance_breakdown.csv, the tangent stiffness
// the derivative of the torque, infinitely stiff bearings the rigid stage,
// and a clearance that only adds lost motion.

#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>

#include <cycloid/analytic/stage_model.h>
#include <cycloid/app/all_parameters.h>
#include <cycloid/reduced/reduced_model.h>
#include <cycloid/support/crank_supports.h>
#include <cycloid/support/needle_bearing.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "reduced_settings.h"

using namespace cycloid;
using dealii::Tensor;

namespace
{
  /** A bearing of @p z rollers of 4 mm x 16 mm on a 12 mm pitch radius. */
  support::NeedleBearing
  bearing(const unsigned int z, const double clearance = 0)
  {
    support::NeedleBearingSize s;
    s.n_rollers       = z;
    s.roller_diameter = 4;
    s.roller_length   = 16;
    s.clearance       = clearance;
    s.pitch_radius    = 12;
    return support::NeedleBearing(s);
  }

  /** The seed stage with the modified profile (clearances 17-20 um), two
   * discs, on needle bearings of auto size with @p clearance [um]. */
  app::AllParameters
  seed_on_bearings(const double clearance = 0)
  {
    app::AllParameters p;
    p.geometry.delta_pin_circle_radius = -0.01;
    p.geometry.delta_pin_radius        = 0.01;
    p.scene.n_discs                    = 2;
    p.bearings.model = support::CrankBearingParameters::Model::needle;
    p.bearings.radial_clearance = clearance;
    return p;
  }

  /** Largest violation of force and moment balance over the discs of
   * @p s (pins plus bearings), each over the disc's largest force or
   * moment; and the bearings' total moment about the disc centres
   * [N mm]. */
  std::pair<double, double>
  equilibrium(const results::StageState       &s,
              const geometry::CycloidGeometry &geo,
              const unsigned int               n_discs)
  {
    double worst = 0, bearing_moment = 0;
    for (unsigned int d = 0; d < n_discs; ++d)
      {
        double fx = 0, fy = 0, m = 0, fs = 0, ms = 0;
        for (const auto &p : s.pins)
          if (p.disc == d)
            {
              fx += p.fx;
              fy += p.fy;
              m -= p.fn * p.arm;
              fs = std::max(fs, p.fn);
              ms = std::max(ms, std::abs(p.fn * p.arm));
            }
        for (const auto &b : s.bearings)
          if (b.disc == d)
            {
              const auto a = geo.crank_hole_centre(d, b.crank, s.crank) -
                             geo.disc_centre(d, s.crank);
              const double mb = a[0] * b.fy - a[1] * b.fx;
              fx += b.fx;
              fy += b.fy;
              m += mb;
              bearing_moment += mb;
              fs = std::max(fs, std::hypot(b.fx, b.fy));
            }
        worst = std::max({worst, std::hypot(fx, fy) / fs, std::abs(m) / ms});
      }
    return {worst, bearing_moment};
  }
} // namespace



TEST(NeedleBearing, EachRollerFollowsPalmgren)
{
  // delta = 3.84e-5 Q^0.9 / l^0.8 per contact, two contacts per roller.
  for (const double q : {1., 250., 4000.})
    {
      const double s = support::NeedleBearing::roller_approach(q, 16.);
      EXPECT_NEAR(s,
                  2 * 3.84e-5 * std::pow(q, 0.9) / std::pow(16., 0.8),
                  1e-15);
      EXPECT_NEAR(support::NeedleBearing::roller_load(s, 16.), q, 1e-10 * q);
    }
  EXPECT_EQ(support::NeedleBearing::roller_load(-1e-3, 16.), 0.);
  // The crank hole moved 5 um towards -x: the roller at +x carries alone
  // of three, its load Palmgren's at 5 um.
  const auto b = bearing(3).response(Tensor<1, 2>({-5e-3, 0.}), 0.);
  EXPECT_EQ(b.rollers_loaded, 1u);
  EXPECT_NEAR(b.max_roller_load,
              support::NeedleBearing::roller_load(5e-3, 16.),
              1e-12 * b.max_roller_load);
  EXPECT_NEAR(b.force[0], b.max_roller_load, 1e-12 * b.max_roller_load);
  EXPECT_NEAR(b.force[1], 0., 1e-9 * b.max_roller_load);
}



TEST(NeedleBearing, ManyRollersShareTheLoadAsStribeck)
{
  // With no clearance and many rollers, Q_max = F Z / J: Stribeck's 4.08
  // for line contact (the integral of cos^(1 + 1/0.9) over the loaded half,
  // 4.085).
  const unsigned int z = 720;
  // The cage half a pitch off, so that no roller sits at 90 degrees.
  const double cage = dealii::numbers::PI / z;
  const auto   b    = bearing(z).response(Tensor<1, 2>({-2e-3, 0.}), cage);
  const double F    = b.force.norm();
  EXPECT_NEAR(b.max_roller_load * z / F, 4.085, 0.005);
  EXPECT_NEAR(support::NeedleBearing::stribeck_number, 4.08, 1e-12);
  EXPECT_EQ(b.rollers_loaded, z / 2);
}



TEST(NeedleBearing, NoForceInsideTheClearanceAndThenPalmgren)
{
  const double c = 8e-3;
  const auto   inside =
    bearing(17, c).response(Tensor<1, 2>({0.6 * c, -0.7 * c}), 0.3);
  EXPECT_EQ(inside.force.norm(), 0.);
  EXPECT_EQ(inside.rollers_loaded, 0u);
  // Beyond it, a roller on the line of the motion is compressed by the
  // excess alone.
  const auto beyond = bearing(17, c).response(Tensor<1, 2>({-c - 4e-3, 0.}), 0);
  EXPECT_NEAR(beyond.max_roller_load,
              support::NeedleBearing::roller_load(4e-3, 16.),
              1e-12 * beyond.max_roller_load);
}



TEST(NeedleBearing, StiffnessIsTheDerivativeOfTheForce)
{
  const auto         law = bearing(17, 2e-3);
  const Tensor<1, 2> d({-4e-3, 3e-3});
  const auto         r = law.response(d, 0.2);
  const double       h = 1e-8;
  for (unsigned int k = 0; k < 2; ++k)
    {
      Tensor<1, 2> dp = d, dm = d;
      dp[k] += h;
      dm[k] -= h;
      const auto fd =
        (law.response(dp, 0.2).force - law.response(dm, 0.2).force) / (2 * h);
      for (unsigned int a = 0; a < 2; ++a)
        EXPECT_NEAR(r.stiffness[a][k], fd[a], 1e-5 * r.stiffness.norm());
    }
}



TEST(CrankBearingParameters, AutoSizesFillTheHoleAndWrongSizesAreRefused)
{
  support::CrankBearingParameters p;
  const auto                      s = p.size(15., 16.);
  EXPECT_DOUBLE_EQ(s.roller_diameter, 3.75);
  EXPECT_DOUBLE_EQ(s.roller_length, 16.);
  EXPECT_DOUBLE_EQ(s.pitch_radius, 15. - 1.875);
  EXPECT_EQ(s.n_rollers, 17u);
  p.n_rollers = 30;
  EXPECT_THROW(p.size(15., 16.), dealii::ExceptionBase);
  p.n_rollers       = 0;
  p.roller_diameter = 16;
  EXPECT_THROW(p.size(15., 16.), dealii::ExceptionBase);
}



TEST(BearingsAnalytic, EachDiscIsInEquilibriumAndTheBearingsCarryTheTorque)
{
  const auto                 p = seed_on_bearings();
  const analytic::StageModel model(p.model_settings());
  for (const double psi : {0., 0.05})
    for (const double T : {300., -1000.})
      {
        const auto s = model.stage_state(model.solve(psi, T, 0.), psi);
        ASSERT_EQ(s.bearings.size(), 6u);
        const auto [worst, moment] = equilibrium(s, model.geometry(), 2);
        EXPECT_LT(worst, 1e-9) << "crank " << psi << ", torque " << T;
        EXPECT_NEAR(moment, T * 1e3, 1e-9 * std::abs(T) * 1e3);
      }
}



TEST(BearingsAnalytic, TheBreakdownSplitsTheOutputWorkExactly)
{
  // T beta = sum_i F_i (approach_i + c_i) + sum_j (-F_j . d_j): the pins'
  // part computed from the written pin forces alone.
  const auto                 p = seed_on_bearings(5);
  const analytic::StageModel model(p.model_settings());
  const double               T = 1000;
  const auto                 s = model.stage_state(model.solve(0., T, 0.), 0.);
  double                     pins_work = 0;
  for (const auto &pin : s.pins)
    pins_work += pin.fn * (pin.approach + std::max(pin.clearance, 0.));
  EXPECT_NEAR(s.breakdown.contacts, pins_work / (T * 1e3), 1e-9 * s.rotation);
  EXPECT_NEAR(s.breakdown.contacts + s.breakdown.bodies + s.breakdown.bearings,
              s.rotation,
              1e-14);
  // With a 5 um clearance the bearings take up about 5 um / 65 mm of the
  // rotation before they carry, on top of their elastic part.
  EXPECT_GT(s.breakdown.bearings, 5e-3 / 65.);
}



TEST(BearingsAnalytic, TangentIsTheDerivativeOfTheTorque)
{
  const auto                 p = seed_on_bearings();
  const analytic::StageModel model(p.model_settings());
  const double               T = 500, dT = 1e-4 * T;
  const auto                 s  = model.solve(0., T, 0.);
  const double               fd = 2 * dT * 1e-3 /
                    (model.solve(0., T + dT, 0.).rotation -
                     model.solve(0., T - dT, 0.).rotation);
  EXPECT_NEAR(s.k_tangent * 1e-3, fd, 1e-4 * fd);
}



TEST(BearingsAnalytic, StiffBearingsAreTheRigidSupport)
{
  // Rollers 10^6 mm long are 10^4 times stiffer than 16 mm ones:
  // the stage then turns and loads its pins as on rigid supports.
  auto p                   = seed_on_bearings();
  p.bearings.roller_length = 1e6;
  const analytic::StageModel stiff(p.model_settings());
  p.bearings.model = support::CrankBearingParameters::Model::rigid;
  const analytic::StageModel rigid(p.model_settings());
  const auto a = stiff.solve(0., 1000., 0.), b = rigid.solve(0., 1000., 0.);
  EXPECT_NEAR(a.rotation, b.rotation, 1e-3 * b.rotation);
  EXPECT_LT(a.breakdown.bearings, 1e-3 * a.rotation);
  double fmax = 0;
  for (const auto &q : b.pins)
    fmax = std::max(fmax, q.force);
  for (unsigned int i = 0; i < a.pins.size(); ++i)
    EXPECT_NEAR(a.pins[i].force, b.pins[i].force, 2e-3 * fmax);
}



TEST(BearingsAnalytic, AClearanceAddsLostMotionOnly)
{
  // A clearance c lets the discs give way before the bearings carry: the
  // take-up grows by about c over the crank circle radius (the discs turn
  // against the eccentrics until a roller in each bearing touches), and
  // beyond it the twist grows too (fewer rollers carry: Stribeck's share
  // with clearance).
  const analytic::StageModel tight(seed_on_bearings(0).model_settings());
  const analytic::StageModel loose(seed_on_bearings(10).model_settings());
  const auto a = tight.solve(0., 1000., 0.), b = loose.solve(0., 1000., 0.);
  EXPECT_GT(b.takeup - a.takeup, 0.5 * 10e-3 / 65.);
  EXPECT_LT(b.takeup - a.takeup, 2. * 10e-3 / 65.);
  EXPECT_GT(b.rotation - b.takeup, a.rotation - a.takeup);
  // The zero-torque limit carries no torque, just beyond it some.
  const auto zero = loose.zero_torque_limit(loose.unloaded_pins(0.), 1, 0.);
  EXPECT_NEAR(zero.rotation, b.takeup, 1e-6 * b.takeup);
  for (const auto &bs : zero.bearings)
    EXPECT_LT(std::hypot(bs.fx, bs.fy), 1e-3);
}



namespace
{
  /** The 2D reduced model's settings of the seed stage, modified
   * profile, one disc on elastic pins, on needle bearings. */
  reduced::ReducedSettings
  reduced_on_bearings()
  {
    app::AllParameters p = seed_on_bearings();
    p.scene.dimension    = 2;
    p.scene.n_discs      = 1;
    return tests::quiet_reduced_settings(p);
  }

  /** One coarse model for the reduced tests (a few seconds to build). */
  class BearingsReduced : public ::testing::Test
  {
  protected:
    static void
    SetUpTestSuite()
    {
      coarse = std::make_unique<reduced::CoarseModel<2>>(
        reduced_on_bearings(), 0., 0., 1, MPI_COMM_WORLD);
    }
    static void
    TearDownTestSuite()
    {
      coarse.reset();
    }
    static std::unique_ptr<reduced::CoarseModel<2>> coarse;
  };
  std::unique_ptr<reduced::CoarseModel<2>> BearingsReduced::coarse;
} // namespace



TEST_F(BearingsReduced, EachDiscIsInEquilibriumAndTheWorkSplits)
{
  const auto                     s = reduced_on_bearings();
  const reduced::ReducedModel<2> model(s, *coarse, 0., 1);
  const analytic::StageModel     geo(s.stage.model_settings());
  const double                   T     = 1000;
  const auto                     state = model.stage_state(model.solve(T, 0.));
  const auto [worst, moment]           = equilibrium(state, geo.geometry(), 1);
  EXPECT_LT(worst, 1e-9);
  EXPECT_NEAR(moment, T * 1e3, 1e-8 * T * 1e3);
  EXPECT_NEAR(state.breakdown.contacts + state.breakdown.bodies +
                state.breakdown.bearings,
              state.rotation,
              1e-14);
  EXPECT_GT(state.breakdown.bodies, 0.);
  EXPECT_GT(state.breakdown.bearings, 0.);
}



TEST_F(BearingsReduced, TangentIsTheDerivativeOfTheTorque)
{
  const reduced::ReducedModel<2> model(reduced_on_bearings(), *coarse, 0., 1);
  const double                   T = 500, dT = 1e-4 * T;
  const auto                     s = model.solve(T, 0.);
  const double                   fd =
    2 * dT /
    (model.solve(T + dT, 0.).rotation - model.solve(T - dT, 0.).rotation);
  EXPECT_NEAR(s.k_tangent, fd, 1e-4 * fd);
}



TEST_F(BearingsReduced, StiffBearingsAreTheRigidSupport)
{
  auto stiff                         = reduced_on_bearings();
  stiff.stage.bearings.roller_length = 1e6;
  auto rigid                         = stiff;
  rigid.stage.bearings.model = support::CrankBearingParameters::Model::rigid;
  const reduced::ReducedModel<2> a(stiff, *coarse, 0., 1),
    b(rigid, *coarse, 0., 1);
  const auto sa = a.solve(1000., 0.), sb = b.solve(1000., 0.);
  EXPECT_NEAR(sa.rotation, sb.rotation, 1e-3 * sb.rotation);
  double fmax = 0;
  for (const auto &q : sb.pins)
    fmax = std::max(fmax, q.force);
  for (unsigned int i = 0; i < sa.pins.size(); ++i)
    EXPECT_NEAR(sa.pins[i].force, sb.pins[i].force, 2e-3 * fmax);
}

// Tests of the analytical models: Hertz closed forms of the pair models,
// the seed's pair-stiffness formula, torque balance and complementarity of
// the load distribution, periodicity, two-disc symmetry, monotonicity in the
// torque, and warm starts.

#include <deal.II/base/numbers.h>

#include <cycloid/analytic/stage_model.h>
#include <cycloid/app/all_parameters.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace cycloid;
using namespace cycloid::analytic;

namespace
{
  constexpr double pi = dealii::numbers::PI;

  app::AllParameters
  seed_case(const std::string &model,
            const double       d_rp  = 0,
            const double       d_rrp = 0)
  {
    app::AllParameters p;
    p.analytic.pair_model              = model;
    p.geometry.delta_pin_circle_radius = d_rp;
    p.geometry.delta_pin_radius        = d_rrp;
    return p;
  }
} // namespace



TEST(PairModels, HertzHalfWidthOfTheDesignCase)
{
  // doc/design-basis.md §2.3: R1 = 10, R2 = 13 mm, E1 = 30000, nu1 = 0.25, E2 =
  // 29120, nu2 = 0.3, F = 3200 N/mm -> half-width 1.20 mm (two convex
  // cylinders: the "profile" has curvature radius -13).
  const LineContactPairStiffness m(1.0,
                                   29120. / (1. - 0.09),
                                   30000. / (1. - 0.0625));
  const PairGeometry             pair{0., -13., 10., 100.};
  EXPECT_NEAR(m.half_width(3200., pair), 1.1997, 1e-4);
  // Closed form a = sqrt(4 F R* / (pi E*)), written out independently.
  const double r_star = 10. * 13. / 23.;
  const double e_star = 1. / ((1 - 0.0625) / 30000. + (1 - 0.09) / 29120.);
  EXPECT_NEAR(m.half_width(3200., pair),
              std::sqrt(4. * 3200. * r_star / (pi * e_star)),
              1e-12);
}



TEST(PairModels, LineContactInversionAndLoadDependentStiffness)
{
  const LineContactPairStiffness m(16., 212000. / 0.91, 212000. / 0.91);
  const PairGeometry             pair{0.5, 8.0, 3.0, 60.};
  double                         previous_k = 0;
  for (const double f : {10., 100., 1000., 5000., 20000.})
    {
      const double d = m.approach(f, pair);
      EXPECT_NEAR(m.force(d, pair), f, 1e-9 * f);
      // Stiffness is the derivative of the force (central difference).
      const double h  = 1e-4 * d;
      const double fd = (m.force(d + h, pair) - m.force(d - h, pair)) / (2 * h);
      EXPECT_NEAR(m.stiffness(d, pair), fd, 1e-5 * fd);
      // Load-dependent: stiffer with load.
      EXPECT_GT(m.stiffness(d, pair), previous_k);
      previous_k = m.stiffness(d, pair);
    }
  // Ordering of a typical pair: rigid pin stiffer than elastic pin.
  const LineContactPairStiffness rigid(16., 212000. / 0.91, 0.);
  EXPECT_GT(rigid.force(1e-3, pair), m.force(1e-3, pair));
}



TEST(PairModels, SeedStiffnessEqualsTheSeedsClosedForm)
{
  // k = pi b E rp S^{3/2} / (4 (1-mu^2) (rp S^{3/2} + 2 rrp T)) with
  // T = K1 (1+zp) cos phi - (1 + zp K1^2), on the concave flank.
  const StageModel model(seed_case("seed").model_settings());
  const auto      &g      = model.geometry();
  const double     lambda = 0.7, b = 16., E = 212000., mu = 0.3;
  const double     K1 = 0.675, rp = g.pin_circle_radius(), rrp = 3.;
  for (const PinLoad &p : model.unloaded_pins(0.05))
    {
      const double phi = p.contact.phase;
      const double S   = 1 + K1 * K1 - 2 * K1 * std::cos(phi);
      const double T   = K1 * (1 + 40) * std::cos(phi) - (1 + 40 * K1 * K1);
      if (T <= 0)
        continue; // convex flank: see SeedPairStiffness
      const double k_seed =
        pi * b * E * rp * std::pow(S, 1.5) /
        (4 * (1 - mu * mu) * (rp * std::pow(S, 1.5) + 2 * rrp * T));
      EXPECT_NEAR(model.pair_model().stiffness(0., p.pair),
                  lambda * k_seed,
                  1e-6 * k_seed)
        << "pin " << p.contact.pin << " phase " << phi;
    }
}



TEST(LoadDistribution, TorqueBalanceAndComplementarity)
{
  for (const std::string model_name : {"seed", "line-contact"})
    for (const double d_rp : {0., -0.01})
      {
        const StageModel model(
          seed_case(model_name, d_rp, 0.01 * (d_rp != 0)).model_settings());
        for (const double torque : {3., 300., -1000., 3000.})
          {
            const LoadState s = model.solve(0.07, torque, 0.);
            // Torque = sum F * arm (N mm -> N m), to round-off.
            double sum = 0;
            for (const PinLoad &p : s.pins)
              sum += p.force * p.contact.arm * 1e-3;
            EXPECT_NEAR(sum, torque, 1e-10 * std::abs(torque))
              << model_name << " " << torque;
            EXPECT_NEAR(s.reaction_torque, torque, 1e-10 * std::abs(torque));
            // Engaged exactly where the rigid approach exceeds the
            // clearance; forces are compressive only.
            unsigned int engaged = 0;
            for (const PinLoad &p : s.pins)
              {
                const double gap = std::max(p.contact.clearance, 0.) -
                                   s.rotation * p.contact.arm;
                EXPECT_GE(p.force, 0.);
                if (gap < -1e-12)
                  {
                    EXPECT_GT(p.force, 0.);
                    EXPECT_NEAR(p.approach, -gap, 1e-15);
                    ++engaged;
                  }
                else
                  EXPECT_EQ(p.force, 0.);
              }
            EXPECT_EQ(engaged, s.pins_in_contact);
            EXPECT_EQ(s.rotation > 0, torque > 0);
            // Tangent stiffness = sum k l^2, checked by a finite
            // difference of the torque.
            const double    h  = 1e-4 * std::abs(torque);
            const LoadState s2 = model.solve(0.07, torque + h, s.rotation);
            EXPECT_NEAR((s2.torque - s.torque) / (s2.rotation - s.rotation),
                        s.k_tangent,
                        2e-3 * s.k_tangent);
          }
      }
}



TEST(LoadDistribution, SeedModelWithoutModificationIsLinear)
{
  // Zero clearances and a linear pair model: K_secant = K_tangent =
  // lambda sum k l^2 at any torque, over the pins of positive arm.
  const StageModel model(seed_case("seed").model_settings());
  const LoadState  s = model.solve(0.0, 500., 0.);
  double           k = 0;
  for (const PinLoad &p : s.pins)
    if (p.contact.arm > 1e-9)
      k += model.pair_model().stiffness(0., p.pair) * p.contact.arm *
           p.contact.arm * 1e-3;
  EXPECT_NEAR(s.k_tangent, k, 1e-9 * k);
  EXPECT_NEAR(s.k_secant(), k, 1e-9 * k);
  EXPECT_NEAR(model.solve(0.0, 50., 0.).k_secant(), k, 1e-9 * k);
}



TEST(LoadDistribution, PeriodicInCrankAngle)
{
  // Exactly periodic only when the load introduction is axisymmetric: the
  // crank holes are not periodic with the tooth pitch, and the disc depth
  // of the line-contact model sees them (see CrankHolesBreakPeriodicity).
  auto prm = seed_case("line-contact", -0.01, 0.01);
  prm.scene.load_introduction =
    parameters::SceneParameters::LoadIntroduction::bore;
  const StageModel model(prm.model_settings());
  const double     T = model.geometry().mesh_period();
  for (const double psi : {0.0, 0.05})
    {
      const LoadState a = model.solve(psi, 800., 0.);
      const LoadState b = model.solve(psi + T, 800., 0.);
      EXPECT_NEAR(a.k_tangent, b.k_tangent, 1e-9 * a.k_tangent);
      EXPECT_NEAR(a.rotation, b.rotation, 1e-12);
      for (unsigned int k = 0; k < a.pins.size(); ++k)
        {
          // Pin j at psi + T carries what pin j-1 carried at psi.
          const unsigned int disc = k / 40, j = k % 40;
          EXPECT_NEAR(b.pins[disc * 40 + j].force,
                      a.pins[disc * 40 + (j + 39) % 40].force,
                      1e-8 * 1000.);
        }
    }
}



TEST(LoadDistribution, TwoDiscsShareOneRotation)
{
  // zp = 40 is even, so disc 1 (half a crank turn ahead) sees the same
  // clearances as disc 0, turned by pi: two discs carry twice the torque at
  // the same rotation, and K doubles.
  // (With the bore as load introduction: the three crank holes sit
  // differently relative to the teeth of the two discs.)
  auto two = seed_case("line-contact", -0.01, 0.01);
  two.scene.load_introduction =
    parameters::SceneParameters::LoadIntroduction::bore;
  auto one          = two;
  one.scene.n_discs = 1;
  const StageModel m1(one.model_settings()), m2(two.model_settings());
  const LoadState  s1 = m1.solve(0.1, 400., 0.);
  const LoadState  s2 = m2.solve(0.1, 800., 0.);
  EXPECT_NEAR(s2.rotation, s1.rotation, 1e-12);
  EXPECT_NEAR(s2.k_tangent, 2. * s1.k_tangent, 1e-9 * s2.k_tangent);
  EXPECT_EQ(s2.pins_in_contact, 2 * s1.pins_in_contact);
}



TEST(LoadDistribution, EngagementAndStiffnessGrowWithTorque)
{
  for (const std::string model_name : {"seed", "line-contact"})
    {
      const StageModel model(
        seed_case(model_name, -0.01, 0.01).model_settings());
      unsigned int pins     = 0;
      double       k_secant = 0, k_tangent = 0, beta = 0;
      for (const double torque : {3., 30., 300., 1000., 3000., 10000.})
        {
          const LoadState s = model.solve(0.02, torque, beta);
          beta              = s.rotation;
          EXPECT_GE(s.pins_in_contact, pins) << model_name << " " << torque;
          EXPECT_GE(s.k_secant(), k_secant) << model_name << " " << torque;
          EXPECT_GE(s.k_tangent, k_tangent) << model_name << " " << torque;
          pins      = s.pins_in_contact;
          k_secant  = s.k_secant();
          k_tangent = s.k_tangent;
        }
      // At low torque few pins engage, at high torque many.
      EXPECT_LE(model.solve(0.02, 3., 0.).pins_in_contact, 4u);
      EXPECT_GE(pins, 12u);
    }
}



TEST(LoadDistribution, WarmStartGivesTheSameStateInFewerIterations)
{
  const StageModel model(
    seed_case("line-contact", -0.01, 0.01).model_settings());
  const LoadState cold = model.solve(0.03, 1000., 0.);
  const LoadState ref  = model.solve(0.0, 1000., 0.);
  const LoadState warm = model.solve(0.03, 1000., ref.rotation);
  EXPECT_NEAR(warm.rotation, cold.rotation, 1e-14);
  EXPECT_LT(warm.iterations, cold.iterations);
}



TEST(LoadDistribution, RigidPinsAreStifferThanElasticPins)
{
  auto rigid       = seed_case("line-contact");
  rigid.scene.pins = parameters::SceneParameters::PinModel::rigid;
  const StageModel e(seed_case("line-contact").model_settings()),
    r(rigid.model_settings());
  EXPECT_GT(r.solve(0., 1000., 0.).k_tangent, e.solve(0., 1000., 0.).k_tangent);
}



TEST(LoadDistribution, CrankHolesBreakExactPeriodicity)
{
  // Three crank holes are not periodic with the 40-pin mesh period; the
  // effect on K is small but not zero.
  const StageModel model(
    seed_case("line-contact", -0.01, 0.01).model_settings());
  const double T = model.geometry().mesh_period();
  const double a = model.solve(0.05, 800., 0.).k_tangent;
  const double b = model.solve(0.05 + T, 800., 0.).k_tangent;
  EXPECT_GT(std::abs(a - b), 1e-6 * a);
  EXPECT_LT(std::abs(a - b), 1e-2 * a);
}



TEST(Deviations, AnalyticModelOfZeroDeviationsIsTheNominalOne)
{
  // Every pin and both discs listed with zero deviations: the same load
  // state to the last bit (the layout is the nominal one exactly).
  auto nominal = seed_case("line-contact", -0.01, 0.01);
  auto zero    = nominal;
  for (unsigned int j = 0; j < zero.geometry.n_pins; ++j)
    {
      geometry::PinDeviation p;
      p.pin = j;
      zero.geometry.pin_deviations.push_back(p);
    }
  for (unsigned int d = 0; d < 2; ++d)
    {
      geometry::DiscDeviation q;
      q.disc = d;
      zero.geometry.disc_deviations.push_back(q);
    }
  const LoadState a = StageModel(nominal.model_settings()).solve(0.1, 800, 0);
  const LoadState b = StageModel(zero.model_settings()).solve(0.1, 800, 0);
  EXPECT_EQ(a.rotation, b.rotation);
  EXPECT_EQ(a.k_tangent, b.k_tangent);
  for (unsigned int k = 0; k < a.pins.size(); ++k)
    EXPECT_EQ(a.pins[k].force, b.pins[k].force);
}



TEST(Deviations, APinPulledOutCarriesNothingAndTheOthersTakeTheTorque)
{
  // Pin 5 of disc 0's loaded side moved 40 um away from the housing
  // centre: its clearance grows by 40 um times the radial part of its
  // normal (more than the elastic approach of 800 N m), so it carries
  // nothing; the torque balance holds with the others, which carry more,
  // and the stage is softer.
  auto                   nominal = seed_case("line-contact", -0.01, 0.01);
  auto                   moved   = nominal;
  geometry::PinDeviation p;
  p.pin       = 5;
  p.radial_um = 40;
  moved.geometry.pin_deviations.push_back(p);
  const StageModel m0(nominal.model_settings()), m1(moved.model_settings());
  const LoadState  a = m0.solve(0.0, 800, 0), b = m1.solve(0.0, 800, 0);
  double           torque = 0;
  for (const PinLoad &q : b.pins)
    {
      torque += q.force * q.contact.arm * 1e-3;
      if (q.contact.disc == 0 && q.contact.pin == 5)
        {
          EXPECT_EQ(q.force, 0.);
          const geometry::CycloidGeometry g0(nominal.geometry);
          const auto                      c0 = g0.pin_contact(0, 5, 0.0);
          const dealii::Tensor<1, 2>      radial(
            {std::cos(2 * pi * 5 / 40), std::sin(2 * pi * 5 / 40)});
          // To first order in the move (its square over rrp left out).
          EXPECT_NEAR(q.contact.clearance - c0.clearance,
                      40e-3 * (c0.normal * radial),
                      40e-3 * 40e-3 / 3.);
          EXPECT_GT(q.contact.clearance - c0.clearance, 0.02);
        }
    }
  EXPECT_NEAR(torque, 800., 1e-6 * 800.);
  EXPECT_GT(b.rotation, a.rotation);
}

// Tests of the cycloid geometry: conjugacy of the standard profile (zero
// gap found by a real closest-point search), periodicity in the crank angle,
// the clearance ranges of the two modification examples of doc/design-basis.md
// §2.1, the law of gearing (normals through the pitch point) and curvature
// closed forms.

#include <deal.II/base/numbers.h>

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/geometry/deviations.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

using namespace cycloid::geometry;

namespace
{
  constexpr double pi = dealii::numbers::PI;

  GeometryParameters
  modified(const double d_rp, const double d_rrp, const double delta_deg = 0)
  {
    GeometryParameters p;
    p.delta_pin_circle_radius   = d_rp;
    p.delta_pin_radius          = d_rrp;
    p.rotation_modification_rad = delta_deg * pi / 180.;
    return p;
  }

  /** Brute-force distance from q to the profile: dense sampling of the
   * whole closed curve and golden-section refinement of the best sample. */
  double
  brute_force_distance(const CycloidGeometry &g, const Point<2> &q)
  {
    const unsigned int zc   = g.parameters().n_teeth;
    const unsigned int n    = 400 * zc;
    const double       h    = 2. * pi * zc / n;
    double             best = 1e300, best_phi = 0;
    for (unsigned int k = 0; k < n; ++k)
      {
        const double d = q.distance(g.profile(k * h).point);
        if (d < best)
          best = d, best_phi = k * h;
      }
    double       a = best_phi - h, b = best_phi + h;
    const double r = (std::sqrt(5.) - 1.) / 2.;
    for (int it = 0; it < 200; ++it)
      {
        const double x1 = b - r * (b - a), x2 = a + r * (b - a);
        if (q.distance(g.profile(x1).point) < q.distance(g.profile(x2).point))
          b = x2;
        else
          a = x1;
      }
    return q.distance(g.profile(0.5 * (a + b)).point);
  }
} // namespace



TEST(Geometry, SeedCaseDerivedQuantities)
{
  const CycloidGeometry g{GeometryParameters()};
  // rp = e zp / K1 = 2.2 * 40 / 0.675 (doc/design-basis.md: 130.370 mm).
  EXPECT_NEAR(g.pin_circle_radius(), 130.370370370, 1e-8);
  EXPECT_NEAR(g.root_radius(), 130.370370370 - 2.2 - 3., 1e-8);
  EXPECT_NEAR(g.profile(0.).point.norm(), g.root_radius(), 1e-10);
  EXPECT_NEAR(g.profile(pi).point.norm(), g.tip_radius(), 1e-10);
  // Closed curve after zc teeth.
  EXPECT_LT(g.profile(0.).point.distance(g.profile(2. * pi * 39).point), 1e-9);
}



TEST(Geometry, StandardProfileIsConjugateForBothDiscsAtAnyCrankAngle)
{
  const CycloidGeometry g{GeometryParameters()};
  const double          tol     = 1e-9 * g.pin_circle_radius();
  double                largest = 0;
  for (const double psi_deg : {0., 3.7, 9., 11.25, 47., 200., 359.})
    for (unsigned int disc = 0; disc < 2; ++disc)
      for (unsigned int j = 0; j < 40; ++j)
        {
          const PinContact c = g.pin_contact(disc, j, psi_deg * pi / 180.);
          EXPECT_LT(std::abs(c.clearance), tol)
            << "disc " << disc << " pin " << j << " psi " << psi_deg;
          largest = std::max(largest, std::abs(c.clearance));
        }
  std::cout << "largest |gap| of the unmodified profile: " << largest << " mm"
            << std::endl;
}



TEST(Geometry, ClosestPointSearchAgreesWithBruteForce)
{
  const CycloidGeometry            g{modified(-0.01, 0.01, 0.005)};
  std::mt19937                     rng(42);
  std::uniform_real_distribution<> angle(0, 2 * pi), radius(121., 136.);
  for (unsigned int k = 0; k < 12; ++k)
    {
      const double   a = angle(rng), r = radius(rng);
      const Point<2> q(r * std::cos(a), r * std::sin(a));
      ProfilePoint   cp;
      const double   d = std::abs(g.signed_distance(q, &cp));
      EXPECT_NEAR(d, brute_force_distance(g, q), 1e-9) << "point " << q;
      // Stationarity: q - P is normal to the curve.
      EXPECT_LT(std::abs((q - cp.point) * cp.derivative) / cp.derivative.norm(),
                1e-9);
    }
}



TEST(Geometry, NormalsPassThroughThePitchPointAndArmsMatchClosedForm)
{
  // Law of gearing for the conjugate profile: every contact normal passes
  // through the pitch point, and the arm about the disc centre is
  // l = e zc sin(phi) / sqrt(S).
  const CycloidGeometry g{GeometryParameters()};
  for (const double psi : {0.1, 1.3})
    for (unsigned int disc = 0; disc < 2; ++disc)
      {
        const Point<2> pitch = g.pitch_point(disc, psi);
        for (const PinContact &c : g.pin_contacts(disc, psi))
          {
            const Tensor<1, 2> d = pitch - c.contact_point;
            EXPECT_LT(std::abs(d[0] * c.normal[1] - d[1] * c.normal[0]), 1e-8);
            EXPECT_NEAR(c.arm, g.closed_form_arm(c.phase), 1e-8);
            // The normal points from the disc to the pin centre.
            const Tensor<1, 2> to_pin = g.pin_centre(c.pin) - c.contact_point;
            EXPECT_NEAR(to_pin * c.normal, 3., 1e-8);
          }
      }
}



TEST(Geometry, ClearancesArePeriodicInTheCrankAngle)
{
  // Period 2 pi / zp: the configuration at psi + T is the one at psi
  // turned by 2 pi/zp, so pin j then sees what pin j-1 saw.
  const CycloidGeometry g{modified(-0.01, 0.012, 0.005)};
  const double          T = g.mesh_period();
  for (const double psi : {0.0, 0.37})
    for (unsigned int disc = 0; disc < 2; ++disc)
      {
        const auto a = g.pin_contacts(disc, psi);
        const auto b = g.pin_contacts(disc, psi + T);
        for (unsigned int j = 0; j < 40; ++j)
          {
            const PinContact &p = a[(j + 39) % 40], &q = b[j];
            EXPECT_NEAR(q.clearance, p.clearance, 1e-12);
            EXPECT_NEAR(q.arm, p.arm, 1e-9);
            EXPECT_NEAR(q.phase, p.phase, 1e-9);
          }
        // And not with a wrong period: half a period changes clearances.
        const auto h    = g.pin_contacts(disc, psi + 0.5 * T);
        double     diff = 0;
        for (unsigned int j = 0; j < 40; ++j)
          diff = std::max(diff, std::abs(h[j].clearance - a[j].clearance));
        EXPECT_GT(diff, 1e-4);
      }
}



TEST(Geometry, ClearanceRangesOfTheDesignExamples)
{
  // doc/design-basis.md §2.1: Delta rp = Delta rrp = +0.01 mm gives 0 to 2.6
  // um; Delta rp = -0.01, Delta rrp = +0.01 gives 17.4 to 20 um.
  const struct
  {
    double d_rp, d_rrp, lo_um, hi_um;
  } cases[] = {{0.01, 0.01, 0.0, 2.6}, {-0.01, 0.01, 17.4, 20.0}};
  for (const auto &c : cases)
    {
      const CycloidGeometry g{modified(c.d_rp, c.d_rrp)};
      double                lo = 1e9, hi = -1e9;
      const unsigned int    n_phases = 30;
      for (unsigned int k = 0; k < n_phases; ++k)
        for (unsigned int disc = 0; disc < 2; ++disc)
          for (const PinContact &p :
               g.pin_contacts(disc, g.mesh_period() * k / n_phases))
            {
              lo = std::min(lo, p.clearance * 1e3);
              hi = std::max(hi, p.clearance * 1e3);
              // First-order closed form; the neglected second-order term
              // is bounded by Delta^2 / rho_root (rho_root ~ 3.5 mm).
              EXPECT_NEAR(p.clearance,
                          g.first_order_clearance(p.phase),
                          0.01 * 0.01 / g.profile(0.).curvature_radius);
            }
      EXPECT_NEAR(lo, c.lo_um, 0.05) << c.d_rp << ", " << c.d_rrp;
      EXPECT_NEAR(hi, c.hi_um, 0.05) << c.d_rp << ", " << c.d_rrp;
    }
}



TEST(Geometry, RotationModificationOpensClearanceOnOneFlank)
{
  // With backlash from Delta rrp, turning the profile clockwise by delta
  // opens the clearance of a pin with arm l by delta * l (the rotation that
  // closes it is counter-clockwise). The central difference over +delta and
  // -delta cancels the second-order term (delta |p|)^2 / rho.
  const CycloidGeometry g0{modified(0., 0.02, 0.)};
  const CycloidGeometry gp{modified(0., 0.02, 0.005)};
  const CycloidGeometry gm{modified(0., 0.02, -0.005)};
  const CycloidGeometry gph{modified(0., 0.02, 0.0025)};
  const CycloidGeometry gmh{modified(0., 0.02, -0.0025)};
  const double          delta = 0.005 * pi / 180.;
  for (const PinContact &c0 : g0.pin_contacts(0, 0.2))
    {
      const double cp = gp.pin_contact(0, c0.pin, 0.2).clearance;
      const double cm = gm.pin_contact(0, c0.pin, 0.2).clearance;
      // Third-order remainder: halving delta divides it by about 8.
      const double ch       = 0.5 * (gph.pin_contact(0, c0.pin, 0.2).clearance -
                               gmh.pin_contact(0, c0.pin, 0.2).clearance);
      const double err_full = std::abs(0.5 * (cp - cm) - delta * c0.arm);
      const double err_half = std::abs(ch - 0.5 * delta * c0.arm);
      EXPECT_LT(err_full, 2e-3 * std::abs(delta * c0.arm) + 1e-9)
        << "pin " << c0.pin;
      EXPECT_LT(err_half, err_full / 6. + 1e-10) << "pin " << c0.pin;
    }
}



TEST(Geometry, CurvatureMatchesTextbookClosedForm)
{
  for (const GeometryParameters &p :
       {GeometryParameters(), modified(-0.01, 0.01)})
    {
      const CycloidGeometry g{p};
      for (const double phi : {0., 0.3, 1.0, 1.9, 2.5, 3.1, 4.0, 5.5})
        {
          const double rho = g.profile(phi).curvature_radius;
          const double cf  = g.closed_form_curvature_radius(phi);
          EXPECT_NEAR(rho, cf, 1e-7 * std::max(1., std::abs(cf)))
            << "phi " << phi;
        }
      // Root concave, tip convex.
      EXPECT_GT(g.profile(0.).curvature_radius, 3.);
      EXPECT_LT(g.profile(pi).curvature_radius, 0.);
    }
}



TEST(Geometry, SeedBacklashIsClearanceAfterRigidTakeUp)
{
  // The seed's Delta(phi) equals the normal clearance minus the clearance
  // closed by the rigid rotation that brings the pin at cos(phi) = K into
  // contact (doc/analytic-model.md).
  for (const GeometryParameters &p :
       {modified(0.01, 0.01), modified(-0.01, 0.01), modified(-0.02, 0.005)})
    {
      const CycloidGeometry g{p};
      const double          K     = g.modified_shortening_coefficient();
      const double          phi_k = std::acos(K);
      const double          beta0 =
        g.first_order_clearance(phi_k) / g.closed_form_arm(phi_k);
      for (const double phi : {0.2, 0.8, phi_k, 1.5, 2.4, 3.0})
        EXPECT_NEAR(g.seed_backlash(phi),
                    g.first_order_clearance(phi) -
                      beta0 * g.closed_form_arm(phi),
                    1e-12);
      EXPECT_NEAR(g.seed_backlash(phi_k), 0., 1e-14);
    }
}



// The stage as data (StageLayout): the nominal layout is the design, and
// each pin's and disc's own data act on its own contacts only, as closed
// forms say they must.

TEST(StageLayout, NominalLayoutIsTheDesign)
{
  const GeometryParameters p;
  const CycloidGeometry    g(p);
  const StageLayout       &l  = g.layout();
  const double             rp = g.pin_circle_radius();
  ASSERT_EQ(l.pins.size(), p.n_pins);
  ASSERT_EQ(l.discs.size(), 2u);
  for (unsigned int j = 0; j < p.n_pins; ++j)
    {
      const double a = 2. * pi * j / p.n_pins;
      EXPECT_NEAR(l.pins[j].centre[0], rp * std::cos(a), 1e-12);
      EXPECT_NEAR(l.pins[j].centre[1], rp * std::sin(a), 1e-12);
      EXPECT_EQ(g.pin_radius(j), p.pin_radius);
    }
  for (unsigned int d = 0; d < 2; ++d)
    {
      EXPECT_EQ(l.discs[d].eccentricity, p.eccentricity);
      EXPECT_EQ(l.discs[d].crank_offset, d == 0 ? 0. : pi);
      EXPECT_EQ(l.discs[d].index_angle, 0.);
    }
  // A geometry built from the nominal layout is the same geometry, bit
  // for bit, at every pin.
  const CycloidGeometry same(p, StageLayout::nominal(p));
  for (const double psi : {0., 0.3, 2.1})
    for (unsigned int d = 0; d < 2; ++d)
      for (unsigned int j = 0; j < p.n_pins; ++j)
        {
          const PinContact a = g.pin_contact(d, j, psi);
          const PinContact b = same.pin_contact(d, j, psi);
          EXPECT_EQ(a.clearance, b.clearance);
          EXPECT_EQ(a.arm, b.arm);
        }
}



TEST(StageLayout, AMovedPinChangesItsOwnClearanceByItsNormalShift)
{
  // Moving a pin's centre by h along its contact normal changes its
  // clearance by h (the closest point stays where it is), and no other
  // pin's; a thicker pin loses its extra radius in clearance.
  const GeometryParameters p = modified(0.01, 0.01);
  const CycloidGeometry    nominal(p);
  const double             psi = 0.4;
  const unsigned int       k = 7, d = 1;
  const PinContact         c = nominal.pin_contact(d, k, psi);
  const double             h = 2e-3, dr = 3e-3;
  StageLayout              moved = nominal.layout();
  moved.pins[k].centre += h * c.normal;
  moved.pins[k].radius += dr;
  const CycloidGeometry g(p, moved);
  EXPECT_NEAR(g.pin_contact(d, k, psi).clearance, c.clearance + h - dr, 1e-10);
  for (unsigned int j = 0; j < p.n_pins; ++j)
    if (j != k)
      {
        EXPECT_EQ(g.pin_contact(d, j, psi).clearance,
                  nominal.pin_contact(d, j, psi).clearance);
      }
}



TEST(StageLayout, AnIndexAngleClosesClearancesByItsArms)
{
  // A disc turned by eps about its centre closes each pin's clearance by
  // eps times the pin's arm (the rigid take-up's law): the central
  // difference of the clearance in eps is -arm; the other disc is
  // untouched.
  const GeometryParameters p = modified(0.01, 0.01);
  const CycloidGeometry    nominal(p);
  const double             psi = 1.1, eps = 1e-6;
  StageLayout              ahead = nominal.layout(), behind = ahead;
  ahead.discs[0].index_angle  = eps;
  behind.discs[0].index_angle = -eps;
  const CycloidGeometry g_ahead(p, ahead), g_behind(p, behind);
  for (unsigned int j = 0; j < p.n_pins; ++j)
    {
      const PinContact c     = nominal.pin_contact(0, j, psi);
      const double     slope = (g_ahead.pin_contact(0, j, psi).clearance -
                            g_behind.pin_contact(0, j, psi).clearance) /
                           (2. * eps);
      EXPECT_NEAR(slope, -c.arm, 1e-5 * std::abs(c.arm) + 1e-6);
      EXPECT_EQ(g_ahead.pin_contact(1, j, psi).clearance,
                nominal.pin_contact(1, j, psi).clearance);
    }
}



TEST(StageLayout, ADiscsOwnModificationsEqualTheGlobalOnes)
{
  // Disc 1 ground with other modifications than disc 0 has exactly the
  // contacts of a stage whose file sets those modifications for both.
  const GeometryParameters p0             = modified(0.01, 0.01);
  const GeometryParameters p1             = modified(-0.005, 0.02, 0.01);
  StageLayout              layout         = StageLayout::nominal(p0);
  layout.discs[1].delta_pin_circle_radius = p1.delta_pin_circle_radius;
  layout.discs[1].delta_pin_radius        = p1.delta_pin_radius;
  layout.discs[1].rotation_modification   = p1.rotation_modification_rad;
  const CycloidGeometry mixed(p0, layout), first(p0), second(p1);
  for (const double psi : {0., 0.7})
    for (unsigned int j = 0; j < p0.n_pins; ++j)
      {
        EXPECT_EQ(mixed.pin_contact(0, j, psi).clearance,
                  first.pin_contact(0, j, psi).clearance);
        EXPECT_EQ(mixed.pin_contact(1, j, psi).clearance,
                  second.pin_contact(1, j, psi).clearance);
      }
}



TEST(StageLayout, AnEccentricityErrorMovesTheDiscCentre)
{
  const GeometryParameters p;
  StageLayout              layout = StageLayout::nominal(p);
  layout.discs[1].eccentricity += 0.004;
  const CycloidGeometry g(p, layout);
  const double          psi = 0.25;
  const Point<2>        c   = g.disc_centre(1, psi);
  EXPECT_NEAR(c.norm(), p.eccentricity + 0.004, 1e-12);
  EXPECT_NEAR(std::atan2(c[1], c[0]), psi + pi - 2. * pi, 1e-12);
  EXPECT_EQ(g.disc_centre(0, psi), CycloidGeometry(p).disc_centre(0, psi));
}



TEST(StageLayout, ALayoutOfTheWrongSizeIsRefused)
{
  const GeometryParameters p;
  StageLayout              layout = StageLayout::nominal(p);
  layout.pins.pop_back();
  EXPECT_THROW(CycloidGeometry(p, layout), dealii::ExceptionBase);
}



TEST(Geometry, ContactPointsOfEveryPinLieOnItsCircle)
{
  // Every pin's contact point lies on the pin, one clearance from it
  // along the normal, and the pins on the line of the eccentricity (at
  // the tooth tip and root, phase 0 and 180 deg) have an arm of exactly
  // 0, as symmetry says. On a 30-pin stage with a modified profile (rp 75,
  // rrp 4, e 1.5 mm) the root pin's arm was 9.66e-14 mm, round-off that a
  // user read as 9.7 mm (issue #51); the seed as well.
  GeometryParameters thirty     = modified(-0.01, 0.01);
  thirty.n_pins                 = 30;
  thirty.n_teeth                = 29;
  thirty.pin_radius             = 4;
  thirty.eccentricity           = 1.5;
  thirty.shortening_coefficient = 1.5 * 30 / 75.;
  thirty.automatic              = {true, true, true, true, true};
  thirty.apply_auto_sizes();
  for (const GeometryParameters &p : {thirty, modified(-0.01, 0.01)})
    {
      const CycloidGeometry g{p};
      for (const double psi : {0., 0.3})
        for (const PinContact &c : g.pin_contacts(0, psi))
          {
            const Tensor<1, 2> to_pin = g.pin_centre(c.pin) - c.contact_point;
            EXPECT_NEAR(to_pin.norm(), p.pin_radius + c.clearance, 1e-9)
              << "zp " << p.n_pins << ", pin " << c.pin << ", psi " << psi;
            EXPECT_NEAR(to_pin * c.normal, to_pin.norm(), 1e-9)
              << "zp " << p.n_pins << ", pin " << c.pin;
            const double phase = std::fmod(c.phase, 2 * pi);
            if (std::min(std::abs(phase), std::abs(phase - pi)) < 1e-6 ||
                std::abs(phase - 2 * pi) < 1e-6)
              EXPECT_EQ(c.arm, 0.) << "zp " << p.n_pins << ", pin " << c.pin
                                   << " at phase " << c.phase;
          }
    }
}



namespace
{
  /** A file with @p text in the system's temporary directory; its path. */
  std::string
  temporary_file(const std::string &name, const std::string &text)
  {
    const std::string path =
      (std::filesystem::temp_directory_path() / ("cycloid-" + name)).string();
    std::ofstream(path) << text;
    return path;
  }

  /** The message of the exception @p f throws, its white space runs
   * made single spaces (deal.II wraps a long message); "" if none. */
  template <typename F>
  std::string
  message_of(F &&f)
  {
    try
      {
        f();
      }
    catch (const std::exception &e)
      {
        std::string text, word;
        for (std::istringstream in(e.what()); in >> word;)
          text += (text.empty() ? "" : " ") + word;
        return text;
      }
    return "";
  }
} // namespace



TEST(Deviations, FilesOfZerosGiveTheNominalLayoutExactly)
{
  const GeometryParameters p    = modified(-0.01, 0.01);
  std::string              pins = "pin,radial_um,tangential_um,radius_um\n";
  for (unsigned int j = 0; j < p.n_pins; ++j)
    pins += std::to_string(j) + ",0,0,0\n";
  const auto laid = deviated_layout(
    p,
    read_pin_deviations(temporary_file("zero-pins.csv", pins), p.n_pins),
    read_disc_deviations(temporary_file(
      "zero-discs.csv",
      "disc,eccentricity_um,angle_arcmin,pin_circle_um,pin_radius_um\n"
      "0,0,0,0,0\n1,0,0,0,0\n")));
  const StageLayout nominal = StageLayout::nominal(p);
  for (unsigned int j = 0; j < p.n_pins; ++j)
    {
      EXPECT_EQ(laid.pins[j].centre, nominal.pins[j].centre);
      EXPECT_EQ(laid.pins[j].radius, nominal.pins[j].radius);
    }
  for (unsigned int d = 0; d < 2; ++d)
    {
      EXPECT_EQ(laid.discs[d].eccentricity, nominal.discs[d].eccentricity);
      EXPECT_EQ(laid.discs[d].index_angle, nominal.discs[d].index_angle);
      EXPECT_EQ(laid.discs[d].delta_pin_radius,
                nominal.discs[d].delta_pin_radius);
    }
}



TEST(Deviations, EachColumnMovesWhatItNames)
{
  // Pin 10 of 40 sits at 90 deg: radial is +y, the counter-clockwise
  // tangent -x. Disc 1's angle in arcmin, its eccentricity and its
  // profile's modifications in um.
  const GeometryParameters p    = modified(-0.01, 0.01);
  const auto               laid = deviated_layout(
    p,
    read_pin_deviations(
      temporary_file("move-pins.csv",
                     "# pin 10 out by 5 um, 3 um along, 2 um thicker\n"
                                   "radius_um,pin,tangential_um,radial_um\n"
                                   "2,10,3,5\n"),
      p.n_pins),
    read_disc_deviations(temporary_file(
      "move-discs.csv",
      "disc,eccentricity_um,angle_arcmin,pin_circle_um,pin_radius_um\n"
                    "1,4,0.5,-2,3\n")));
  const StageLayout nominal = StageLayout::nominal(p);
  const auto        moved   = laid.pins[10].centre - nominal.pins[10].centre;
  EXPECT_NEAR(moved[0], -3e-3, 1e-12);
  EXPECT_NEAR(moved[1], 5e-3, 1e-12);
  EXPECT_NEAR(laid.pins[10].radius, p.pin_radius + 2e-3, 1e-15);
  EXPECT_EQ(laid.pins[11].centre, nominal.pins[11].centre);
  EXPECT_NEAR(laid.discs[1].eccentricity, p.eccentricity + 4e-3, 1e-15);
  EXPECT_NEAR(laid.discs[1].index_angle, 0.5 / 60. * pi / 180., 1e-18);
  EXPECT_NEAR(laid.discs[1].delta_pin_circle_radius, -0.01 - 2e-3, 1e-15);
  EXPECT_NEAR(laid.discs[1].delta_pin_radius, 0.01 + 3e-3, 1e-15);
  EXPECT_EQ(laid.discs[0].eccentricity, nominal.discs[0].eccentricity);
}



TEST(Deviations, ThickerPinsInDiscsGroundForThemKeepEveryClearance)
{
  // Every pin 10 um thicker and both discs ground with Delta rrp 10 um
  // more: the equidistant profile moves out by exactly what the pins
  // grew, so every clearance and arm is the nominal stage's.
  const GeometryParameters p    = modified(-0.01, 0.01);
  std::string              pins = "pin,radial_um,tangential_um,radius_um\n";
  for (unsigned int j = 0; j < p.n_pins; ++j)
    pins += std::to_string(j) + ",0,0,10\n";
  const CycloidGeometry thick(
    p,
    deviated_layout(
      p,
      read_pin_deviations(temporary_file("thick-pins.csv", pins), p.n_pins),
      read_disc_deviations(temporary_file(
        "thick-discs.csv",
        "disc,eccentricity_um,angle_arcmin,pin_circle_um,pin_radius_um\n"
        "0,0,0,0,10\n1,0,0,0,10\n"))));
  const CycloidGeometry nominal(p);
  for (unsigned int disc = 0; disc < 2; ++disc)
    for (unsigned int j = 0; j < p.n_pins; ++j)
      {
        const PinContact a = thick.pin_contact(disc, j, 0.2);
        const PinContact b = nominal.pin_contact(disc, j, 0.2);
        EXPECT_NEAR(a.clearance, b.clearance, 1e-12) << "pin " << j;
        EXPECT_NEAR(a.arm, b.arm, 1e-9) << "pin " << j;
      }
}



TEST(Deviations, ABadFileIsNamedWithItsLineAndColumn)
{
  const unsigned int n = 40;
  const auto pin       = [n](const std::string &name, const std::string &text) {
    return message_of(
      [&] { read_pin_deviations(temporary_file(name, text), n); });
  };
  const std::string header = "pin,radial_um,tangential_um,radius_um\n";
  const std::string nan    = pin("bad-number.csv", header + "3,1,abc,0\n");
  EXPECT_NE(nan.find("Deviations/Pin deviations file"), std::string::npos);
  EXPECT_NE(nan.find("bad-number.csv"), std::string::npos) << nan;
  EXPECT_NE(nan.find("line 2, column 'tangential_um': 'abc' is not a number"),
            std::string::npos)
    << nan;
  EXPECT_NE(pin("range.csv", header + "1,0,0,0\n40,0,0,0\n")
              .find("line 3, column 'pin': 40 is not an index from 0 to 39"),
            std::string::npos);
  EXPECT_NE(pin("twice.csv", header + "7,0,0,0\n# again\n7,1,0,0\n")
              .find("line 4, column 'pin': pin 7 is listed twice (also on "
                    "line 2)"),
            std::string::npos);
  EXPECT_NE(pin("no-column.csv", "pin,radial_um,radius_um\n1,0,0\n")
              .find("line 1: no column 'tangential_um'"),
            std::string::npos);
  EXPECT_NE(pin("short-row.csv", header + "1,0,0\n")
              .find("line 2: 3 values for 4 columns"),
            std::string::npos);
  EXPECT_NE(message_of([] {
              read_pin_deviations("/nonexistent/p.csv", 40);
            }).find("'/nonexistent/p.csv': cannot be read"),
            std::string::npos);
  EXPECT_NE(message_of([] {
              read_disc_deviations(temporary_file(
                "disc-range.csv",
                "disc,eccentricity_um,angle_arcmin,pin_circle_um,"
                "pin_radius_um\n2,0,0,0,0\n"));
            }).find("Deviations/Disc deviations file"),
            std::string::npos);
}

#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>

#include <cycloid/geometry/cycloid_geometry.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>

namespace cycloid
{
  namespace geometry
  {
    namespace
    {
      using complex = std::complex<double>;

      constexpr double pi = dealii::numbers::PI;

      inline Tensor<1, 2>
      to_tensor(const complex &z)
      {
        Tensor<1, 2> t;
        t[0] = z.real();
        t[1] = z.imag();
        return t;
      }

      inline double
      cross(const Tensor<1, 2> &a, const Tensor<1, 2> &b)
      {
        return a[0] * b[1] - a[1] * b[0];
      }

      inline Tensor<1, 2>
      rotate(const Tensor<1, 2> &v, const double angle)
      {
        const double c = std::cos(angle), s = std::sin(angle);
        Tensor<1, 2> w;
        w[0] = c * v[0] - s * v[1];
        w[1] = s * v[0] + c * v[1];
        return w;
      }

      /** Reduce an angle to [0, 2 pi). */
      inline double
      wrap_two_pi(const double x)
      {
        double y = std::fmod(x, 2. * pi);
        if (y < 0)
          y += 2. * pi;
        return (y >= 2. * pi) ? 0. : y;
      }
    } // namespace



    void
    GeometryParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using dealii::Patterns::Double;
      using dealii::Patterns::Integer;
      prm.enter_subsection("Geometry");
      {
        prm.declare_entry("Number of pins",
                          "40",
                          Integer(3, 1000),
                          "Number of pins zp [-].");
        prm.declare_entry("Number of cycloid teeth",
                          "39",
                          Integer(2, 999),
                          "Number of cycloid teeth zc [-]; must be zp - 1.");
        prm.declare_entry("Pin radius", "3", Double(0), "Pin radius rrp [mm].");
        prm.declare_entry("Eccentricity",
                          "2.2",
                          Double(0),
                          "Crank eccentricity e [mm].");
        prm.declare_entry(
          "Shortening coefficient",
          "0.675",
          Double(0, 1),
          "Shortening coefficient K1 = e zp / rp [-], 0 < K1 < 1; the pin "
          "circle radius rp follows from it.");
        prm.declare_entry(
          "Tooth width",
          "16",
          Double(0),
          "Tooth (disc) width b [mm]. 2D (plane strain) results "
          "are reported for this width.");
        prm.declare_entry(
          "Pin circle radius modification",
          "0",
          Double(-10, 10),
          "Profile modification Delta rp [mm] (shift of the generating pin "
          "circle; negative opens clearance at the root).");
        prm.declare_entry(
          "Pin radius modification",
          "0",
          Double(-10, 10),
          "Profile modification Delta rrp [mm] (equidistant modification: "
          "generating pin radius rrp + Delta rrp; the real pins keep rrp).");
        prm.declare_entry("Rotation modification",
                          "0",
                          Double(-10, 10),
                          "Profile modification delta [degrees]: the profile "
                          "is turned clockwise by delta in the disc frame "
                          "(the seed's sign convention).");
        prm.declare_entry("Bore radius",
                          "25",
                          Double(0),
                          "Radius of the disc's central bore [mm].");
        prm.declare_entry("Number of crank holes",
                          "3",
                          Integer(0, 12),
                          "Number of crank-shaft holes per disc [-] "
                          "(0 allowed).");
        prm.declare_entry("Crank hole radius",
                          "15",
                          Double(0),
                          "Radius of each crank-shaft hole [mm].");
        prm.declare_entry(
          "Crank hole circle radius",
          "65",
          Double(0),
          "Radius of the circle through the crank-hole centres [mm].");
        prm.declare_entry("Axial gap between discs",
                          "2",
                          Double(0),
                          "Axial gap between the two discs of a 3D scene "
                          "[mm].");
        prm.declare_entry("Housing wall thickness",
                          "15",
                          Double(0),
                          "Radial wall thickness of the pin housing outside "
                          "the pin circle [mm]; the housing ring spans rp to "
                          "rp + this, with a groove of radius rrp per pin.");
      }
      prm.leave_subsection();
    }



    void
    GeometryParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      {
        n_pins                 = prm.get_integer("Number of pins");
        n_teeth                = prm.get_integer("Number of cycloid teeth");
        pin_radius             = prm.get_double("Pin radius");
        eccentricity           = prm.get_double("Eccentricity");
        shortening_coefficient = prm.get_double("Shortening coefficient");
        tooth_width            = prm.get_double("Tooth width");
        delta_pin_circle_radius =
          prm.get_double("Pin circle radius modification");
        delta_pin_radius = prm.get_double("Pin radius modification");
        rotation_modification_rad =
          prm.get_double("Rotation modification") * pi / 180.;
        bore_radius              = prm.get_double("Bore radius");
        n_crank_holes            = prm.get_integer("Number of crank holes");
        crank_hole_radius        = prm.get_double("Crank hole radius");
        crank_hole_circle_radius = prm.get_double("Crank hole circle radius");
        axial_gap                = prm.get_double("Axial gap between discs");
        housing_thickness        = prm.get_double("Housing wall thickness");
      }
      prm.leave_subsection();
    }



    CycloidGeometry::CycloidGeometry(const GeometryParameters &parameters)
      : prm(parameters)
      , zp(parameters.n_pins)
      , zc(parameters.n_teeth)
      , rp(parameters.shortening_coefficient > 0 ?
             parameters.eccentricity * parameters.n_pins /
               parameters.shortening_coefficient :
             0.)
      , i_h(static_cast<double>(parameters.n_pins) /
            std::max(1u, parameters.n_teeth))
      , big_r(rp + parameters.delta_pin_circle_radius)
      , small_r(parameters.pin_radius + parameters.delta_pin_radius)
      , k_mod(big_r > 0 ? parameters.eccentricity * parameters.n_pins / big_r :
                          0.)
      , delta(parameters.rotation_modification_rad)
    {
      validate();
    }



    namespace
    {
      /** Throw naming Geometry/@p name unless @p value is positive. */
      void
      require_positive(const double value, const char *name)
      {
        AssertThrow(value > 0,
                    dealii::ExcMessage(std::string("Geometry/") + name +
                                       " must be positive, got " +
                                       std::to_string(value) + "."));
      }



      /** Positive pin radius, eccentricity, tooth width and bore radius;
       * K1 in (0, 1); zc = zp - 1. Throws dealii::ExcMessage. */
      void
      check_inputs(const GeometryParameters &prm)
      {
        using dealii::ExcMessage;
        require_positive(prm.pin_radius, "Pin radius");
        require_positive(prm.eccentricity, "Eccentricity");
        require_positive(prm.tooth_width, "Tooth width");
        require_positive(prm.bore_radius, "Bore radius");
        AssertThrow(prm.shortening_coefficient > 0 &&
                      prm.shortening_coefficient < 1,
                    ExcMessage("Geometry/Shortening coefficient K1 must lie in "
                               "(0, 1), got " +
                               std::to_string(prm.shortening_coefficient) +
                               "."));
        AssertThrow(prm.n_teeth + 1 == prm.n_pins,
                    ExcMessage("Geometry/Number of cycloid teeth must equal "
                               "Number of pins - 1 (zc = zp - 1), got zp = " +
                               std::to_string(prm.n_pins) +
                               ", zc = " + std::to_string(prm.n_teeth) + "."));
      }



      /** The profile modifications keep the generating pin radius
       * @p small_r = rrp + Delta rrp positive and the modified shortening
       * coefficient @p k_mod in (0, 1). Throws dealii::ExcMessage. */
      void
      check_modifications(const double small_r, const double k_mod)
      {
        using dealii::ExcMessage;
        AssertThrow(small_r > 0,
                    ExcMessage("Geometry/Pin radius modification makes the "
                               "generating pin radius rrp + Delta rrp = " +
                               std::to_string(small_r) + " mm non-positive."));
        AssertThrow(k_mod > 0 && k_mod < 1,
                    ExcMessage("Geometry/Pin circle radius modification makes "
                               "the modified shortening coefficient e zp/(rp + "
                               "Delta rp) = " +
                               std::to_string(k_mod) + " leave (0, 1)."));
      }



      /** Neighbouring pins (@p zp of them on the circle @p rp) do not
       * overlap. Throws dealii::ExcMessage. */
      void
      check_pin_spacing(const GeometryParameters &prm,
                        const double              rp,
                        const unsigned int        zp)
      {
        using dealii::ExcMessage;
        // Neighbouring pins must not overlap: chord 2 rp sin(pi/zp) > 2 rrp.
        const double chord = 2. * rp * std::sin(pi / zp);
        AssertThrow(2. * prm.pin_radius < chord,
                    ExcMessage("Geometry/Pin radius: neighbouring pins overlap "
                               "(2 rrp = " +
                               std::to_string(2. * prm.pin_radius) +
                               " mm >= pin spacing 2 rp sin(pi/zp) = " +
                               std::to_string(chord) + " mm)."));
      }



      /** The profile does not undercut: @p margin is
       * CycloidGeometry::undercut_margin() for the generating pin radius
       * @p small_r. Throws dealii::ExcMessage. */
      void
      check_undercut(const double margin, const double small_r)
      {
        using dealii::ExcMessage;
        // Undercut: the profile's curvature radius passes through zero where
        // the convex part of the pin-centre curve is sharper than r.
        std::ostringstream msg;
        msg << "Geometry: the cycloid profile undercuts (its curvature radius "
               "passes through zero): the smallest convex curvature radius of "
               "the pin-centre curve is "
            << margin + small_r << " mm, less than the generating pin radius "
            << small_r
            << " mm. Reduce Pin radius (+ Pin radius modification) or "
               "Eccentricity / Shortening coefficient.";
        AssertThrow(margin > 0, ExcMessage(msg.str()));
      }



      /** The modified disc @p g does not overlap a pin at rest (pin
       * circle @p rp, @p zc teeth, ratio @p i_h). Throws dealii::ExcMessage. */
      void
      check_rest_clearance(const CycloidGeometry    &g,
                           const GeometryParameters &prm,
                           const double              rp,
                           const unsigned int        zc,
                           const double              i_h)
      {
        using dealii::ExcMessage;
        // The modified disc must not overlap a pin at rest: every pin centre
        // sweeps the nominal pin-centre curve in the disc frame, so sample one
        // tooth of it and measure the clearance by a closest-point search.
        const unsigned int n_samples = 720;
        double             worst     = std::numeric_limits<double>::max();
        double             worst_phi = 0;
        for (unsigned int k = 0; k < n_samples; ++k)
          {
            const double  phi = 2. * pi * k / n_samples;
            const complex q   = rp * std::polar(1., -phi / zc) -
                              prm.eccentricity * std::polar(1., -i_h * phi);
            const double c =
              g.signed_distance(Point<2>(q.real(), q.imag())) - prm.pin_radius;
            if (c < worst)
              {
                worst     = c;
                worst_phi = phi;
              }
          }
        std::ostringstream msg;
        msg << "Geometry: the profile modifications (Pin circle radius "
               "modification = "
            << prm.delta_pin_circle_radius
            << " mm, Pin radius modification = " << prm.delta_pin_radius
            << " mm, Rotation modification = "
            << prm.rotation_modification_rad * 180. / pi
            << " deg) make the disc overlap a pin at rest by " << -worst * 1e3
            << " um (at tooth phase " << worst_phi * 180. / pi
            << " deg). The scene cannot start from a negative clearance.";
        AssertThrow(worst > -1e-7, ExcMessage(msg.str()));
      }



      /** The housing wall outlasts its grooves. Throws dealii::ExcMessage. */
      void
      check_housing(const GeometryParameters &prm)
      {
        using dealii::ExcMessage;
        AssertThrow(prm.housing_thickness > 1.5 * prm.pin_radius,
                    ExcMessage(
                      "Geometry/Housing wall thickness must exceed 1.5 "
                      "Pin radius so that the grooves leave a wall."));
      }



      /** Bore and crank holes fit inside the root circle @p root and do
       * not cut into each other. Throws dealii::ExcMessage. */
      void
      check_holes(const GeometryParameters &prm, const double root)
      {
        using dealii::ExcMessage;
        // Bore and crank holes must fit inside the root circle.
        AssertThrow(prm.bore_radius < root,
                    ExcMessage("Geometry/Bore radius " +
                               std::to_string(prm.bore_radius) +
                               " mm does not fit inside the root radius " +
                               std::to_string(root) + " mm."));
        if (prm.n_crank_holes > 0)
          {
            require_positive(prm.crank_hole_radius, "Crank hole radius");
            require_positive(prm.crank_hole_circle_radius,
                             "Crank hole circle radius");
            AssertThrow(prm.crank_hole_circle_radius - prm.crank_hole_radius >
                          prm.bore_radius,
                        ExcMessage("Geometry/Crank hole radius and Crank hole "
                                   "circle radius: the crank holes cut into "
                                   "the bore."));
            AssertThrow(prm.crank_hole_circle_radius + prm.crank_hole_radius <
                          root,
                        ExcMessage("Geometry/Crank hole radius and Crank hole "
                                   "circle radius: the crank holes cut the "
                                   "tooth root (root radius " +
                                   std::to_string(root) + " mm)."));
            if (prm.n_crank_holes > 1)
              AssertThrow(prm.crank_hole_radius <
                            prm.crank_hole_circle_radius *
                              std::sin(pi / prm.n_crank_holes),
                          ExcMessage("Geometry/Crank hole radius: neighbouring "
                                     "crank holes overlap."));
          }
      }
    } // namespace



    void
    CycloidGeometry::validate() const
    {
      // Cheap parameter checks first, so that the message names the input
      // before a derived quantity (undercut, clearance) trips over it.
      check_inputs(prm);
      check_modifications(small_r, k_mod);
      check_pin_spacing(prm, rp, zp);
      check_undercut(undercut_margin(), small_r);
      check_rest_clearance(*this, prm, rp, zc, i_h);
      check_housing(prm);
      check_holes(prm, root_radius());
    }



    double
    CycloidGeometry::root_radius() const
    {
      return big_r - prm.eccentricity - small_r;
    }



    double
    CycloidGeometry::tip_radius() const
    {
      return big_r + prm.eccentricity - small_r;
    }



    double
    CycloidGeometry::mesh_period() const
    {
      return 2. * pi / zp;
    }



    double
    CycloidGeometry::s_function(const double phi) const
    {
      return 1. + k_mod * k_mod - 2. * k_mod * std::cos(phi);
    }



    void
    CycloidGeometry::evaluate(const double  phi,
                              Tensor<1, 2> &p,
                              Tensor<1, 2> &dp,
                              Tensor<1, 2> &ddp,
                              Tensor<1, 2> &normal) const
    {
      const complex I(0., 1.);
      const double  inv_zc = 1. / zc;
      const complex ea     = std::polar(1., -phi * inv_zc);
      const complex eg     = std::polar(1., -i_h * phi);

      // Pin-centre curve C and its unnormalised outward normal u.
      const complex c   = big_r * ea - prm.eccentricity * eg;
      const complex u   = ea - k_mod * eg;
      const complex du  = -I * inv_zc * ea + I * i_h * k_mod * eg;
      const complex ddu = -inv_zc * inv_zc * ea + i_h * i_h * k_mod * eg;
      const complex dc  = -I * (big_r * inv_zc) * u;
      const complex ddc = -I * (big_r * inv_zc) * du;

      const double S    = s_function(phi);
      const double sphi = std::sin(phi), cphi = std::cos(phi);
      const double s  = 1. / std::sqrt(S);
      const double s3 = s * s * s;
      const double ds = -k_mod * sphi * s3;
      const double dds =
        -k_mod * cphi * s3 + 3. * k_mod * k_mod * sphi * sphi * s3 * s * s;

      const complex P   = c - small_r * u * s;
      const complex dP  = dc - small_r * (du * s + u * ds);
      const complex ddP = ddc - small_r * (ddu * s + 2. * du * ds + u * dds);

      const complex turn = std::polar(1., -delta);
      p                  = to_tensor(turn * P);
      dp                 = to_tensor(turn * dP);
      ddp                = to_tensor(turn * ddP);
      normal             = to_tensor(turn * u * s);
    }



    ProfilePoint
    CycloidGeometry::profile(const double phi) const
    {
      Tensor<1, 2> p, dp, ddp, n;
      evaluate(phi, p, dp, ddp, n);
      ProfilePoint result;
      result.phi        = phi;
      result.point      = Point<2>(p);
      result.derivative = dp;
      result.normal     = n;

      // Signed curvature kappa = (P' x P'') / |P'|^3 of the curve as
      // traversed; its centre lies at P + (1/kappa) * left normal. Convert
      // to "positive where the centre of curvature is outside the disc".
      const double speed = dp.norm();
      const double kappa = cross(dp, ddp) / (speed * speed * speed);
      Tensor<1, 2> left;
      left[0]           = -dp[1] / speed;
      left[1]           = dp[0] / speed;
      const double side = (left * n) >= 0 ? 1. : -1.;
      result.curvature_radius =
        (kappa != 0.) ? side / kappa : std::numeric_limits<double>::infinity();
      return result;
    }



    Tensor<1, 2>
    CycloidGeometry::profile_second_derivative(const double phi) const
    {
      Tensor<1, 2> p, dp, ddp, n;
      evaluate(phi, p, dp, ddp, n);
      return ddp;
    }



    ProfilePoint
    CycloidGeometry::closest_point(const Point<2> &q) const
    {
      // Initial window from the polar angle of q: the profile point of
      // parameter phi lies near polar angle -phi/zc - delta.
      const double theta = std::atan2(q[1], q[0]) + delta;
      const double phi0  = -theta * zc;

      // Cheap evaluation of the point only, for the coarse sampling.
      const complex turn   = std::polar(1., -delta);
      const double  inv_zc = 1. / zc;
      const complex qz(q[0], q[1]);
      const auto    distance2 = [&](const double phi) {
        const complex ea = std::polar(1., -phi * inv_zc);
        const complex eg = std::polar(1., -i_h * phi);
        const double  s  = 1. / std::sqrt(s_function(phi));
        const complex P  = turn * (big_r * ea - prm.eccentricity * eg -
                                  small_r * s * (ea - k_mod * eg));
        return std::norm(P - qz);
      };

      // The window of 2.5 teeth is wide enough: the polar angle of P(phi)
      // departs from -phi/zc by less than (e + r)/root radius, i.e. by less
      // than (e + r) zc / root radius ~ 1.6 rad of phi for the seed case.
      const unsigned int n_samples = 32;
      const double       lo        = phi0 - 1.25 * pi;
      const double       h         = 2.5 * pi / n_samples;
      double             best      = std::numeric_limits<double>::max();
      unsigned int       best_k    = 0;
      for (unsigned int k = 0; k <= n_samples; ++k)
        {
          const double d2 = distance2(lo + k * h);
          if (d2 < best)
            {
              best   = d2;
              best_k = k;
            }
        }

      // Safeguarded Newton on g(phi) = (P - q) . P' inside the bracket of
      // the best sample's neighbours.
      double     a        = lo + (best_k == 0 ? 0 : best_k - 1) * h;
      double     b        = lo + std::min(best_k + 1, n_samples) * h;
      double     phi      = lo + best_k * h;
      const auto g_and_dg = [&](const double x, double &g, double &dg) {
        Tensor<1, 2> p, dp, ddp, n;
        evaluate(x, p, dp, ddp, n);
        const Tensor<1, 2> d = p - q;
        g                    = d * dp;
        dg                   = dp * dp + d * ddp;
      };
      double ga, gb, dg;
      g_and_dg(a, ga, dg);
      g_and_dg(b, gb, dg);
      const bool bracketed = (ga <= 0 && gb >= 0);
      for (unsigned int it = 0; it < 60; ++it)
        {
          double g;
          g_and_dg(phi, g, dg);
          if (bracketed)
            {
              if (g < 0)
                a = phi;
              else
                b = phi;
            }
          double next = (dg > 0) ? phi - g / dg : 0.5 * (a + b);
          if (bracketed && (next <= a || next >= b))
            next = 0.5 * (a + b);
          const double step = std::abs(next - phi);
          phi               = next;
          if (step < 1e-15 * (1. + std::abs(phi)))
            break;
        }
      return profile(phi);
    }



    double
    CycloidGeometry::signed_distance(const Point<2> &q,
                                     ProfilePoint   *closest) const
    {
      const ProfilePoint cp = closest_point(q);
      if (closest != nullptr)
        *closest = cp;
      const Tensor<1, 2> d = q - cp.point;
      return (d * cp.normal >= 0 ? 1. : -1.) * d.norm();
    }



    Point<2>
    CycloidGeometry::crank_hole_centre(const unsigned int k) const
    {
      const double a = 2. * pi * k / std::max(1u, prm.n_crank_holes);
      return Point<2>(prm.crank_hole_circle_radius * std::cos(a),
                      prm.crank_hole_circle_radius * std::sin(a));
    }



    Point<2>
    CycloidGeometry::crank_hole_centre(const unsigned int disc,
                                       const unsigned int k,
                                       const double       psi) const
    {
      return to_housing(disc, psi, crank_hole_centre(k));
    }



    Point<2>
    CycloidGeometry::pin_centre(const unsigned int j) const
    {
      const double angle = 2. * pi * j / zp;
      return Point<2>(rp * std::cos(angle), rp * std::sin(angle));
    }



    double
    CycloidGeometry::disc_crank_angle(const unsigned int disc, const double psi)
    {
      return psi + (disc == 0 ? 0. : pi);
    }



    Point<2>
    CycloidGeometry::disc_centre(const unsigned int disc,
                                 const double       psi) const
    {
      const double a = disc_crank_angle(disc, psi);
      return Point<2>(prm.eccentricity * std::cos(a),
                      prm.eccentricity * std::sin(a));
    }



    double
    CycloidGeometry::disc_rotation(const unsigned int disc,
                                   const double       psi) const
    {
      return -disc_crank_angle(disc, psi) / zc;
    }



    Point<2>
    CycloidGeometry::to_housing(const unsigned int disc,
                                const double       psi,
                                const Point<2>    &p_disc) const
    {
      return disc_centre(disc, psi) +
             rotate(Tensor<1, 2>(p_disc), disc_rotation(disc, psi));
    }



    Point<2>
    CycloidGeometry::to_disc(const unsigned int disc,
                             const double       psi,
                             const Point<2>    &q_housing) const
    {
      return Point<2>(
        rotate(q_housing - disc_centre(disc, psi), -disc_rotation(disc, psi)));
    }



    PinContact
    CycloidGeometry::pin_contact(const unsigned int disc,
                                 const unsigned int j,
                                 const double       psi) const
    {
      const Point<2> q = to_disc(disc, psi, pin_centre(j));
      ProfilePoint   cp;
      const double   d     = signed_distance(q, &cp);
      const double   angle = disc_rotation(disc, psi);
      PinContact     result;
      result.disc             = disc;
      result.pin              = j;
      result.clearance        = d - prm.pin_radius;
      result.contact_point    = to_housing(disc, psi, cp.point);
      result.normal           = rotate(cp.normal, angle);
      result.arm              = cross(Tensor<1, 2>(cp.point), cp.normal);
      result.phase            = wrap_two_pi(cp.phi);
      result.curvature_radius = cp.curvature_radius;
      result.disc_centre      = disc_centre(disc, psi);
      return result;
    }



    std::vector<PinContact>
    CycloidGeometry::pin_contacts(const unsigned int disc,
                                  const double       psi) const
    {
      std::vector<PinContact> result;
      result.reserve(zp);
      for (unsigned int j = 0; j < zp; ++j)
        result.push_back(pin_contact(disc, j, psi));
      return result;
    }



    Point<2>
    CycloidGeometry::pitch_point(const unsigned int disc,
                                 const double       psi) const
    {
      const double a = disc_crank_angle(disc, psi);
      const double d = prm.eccentricity * zp;
      return Point<2>(d * std::cos(a), d * std::sin(a));
    }



    double
    CycloidGeometry::closed_form_curvature_radius(const double phi) const
    {
      const double S = s_function(phi);
      const double T =
        k_mod * (1. + zp) * std::cos(phi) - (1. + zp * k_mod * k_mod);
      return big_r * S * std::sqrt(S) / T + small_r;
    }



    double
    CycloidGeometry::first_order_clearance(const double phi) const
    {
      const double S = s_function(phi);
      return prm.delta_pin_radius - prm.delta_pin_circle_radius *
                                      (1. - k_mod * std::cos(phi)) /
                                      std::sqrt(S);
    }



    double
    CycloidGeometry::seed_backlash(const double phi) const
    {
      const double S  = s_function(phi);
      const double sq = std::sqrt(S);
      return prm.delta_pin_radius * (1. - std::sin(phi) / sq) -
             prm.delta_pin_circle_radius *
               (1. - k_mod * std::cos(phi) -
                std::sqrt(1. - k_mod * k_mod) * std::sin(phi)) /
               sq;
    }



    double
    CycloidGeometry::closed_form_arm(const double phi) const
    {
      return prm.eccentricity * zc * std::sin(phi) / std::sqrt(s_function(phi));
    }



    double
    CycloidGeometry::undercut_margin() const
    {
      // rho_C = R S^{3/2} / T is the pin-centre curve's curvature radius
      // (negative on the convex part); sample half a tooth (symmetric).
      double             smallest  = std::numeric_limits<double>::max();
      const unsigned int n_samples = 2000;
      for (unsigned int k = 0; k <= n_samples; ++k)
        {
          const double phi = pi * k / n_samples;
          const double S   = s_function(phi);
          const double T =
            k_mod * (1. + zp) * std::cos(phi) - (1. + zp * k_mod * k_mod);
          if (T < 0)
            smallest = std::min(smallest, -big_r * S * std::sqrt(S) / T);
        }
      return smallest - small_r;
    }
  } // namespace geometry
} // namespace cycloid

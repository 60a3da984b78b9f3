#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/parameters/or_auto.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <iomanip>
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
                          "auto",
                          parameters::OrAuto(Integer(2, 999)),
                          "Number of cycloid teeth zc [-]; must be zp - 1. "
                          "auto: zp - 1.");
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
        prm.declare_entry(
          "Bore radius",
          "auto",
          parameters::OrAuto(Double(0)),
          "Radius of the disc's central bore [mm], > 0 and below the root "
          "radius. auto: 25 mm x (rp - e - rrp) / 125.170 mm, the seed's bore "
          "scaled by the ratio of the root radii (rp = e zp / K1); 25 mm for "
          "the seed geometry.");
        prm.declare_entry("Number of crank holes",
                          "3",
                          Integer(0, 12),
                          "Number of crank-shaft holes per disc [-] "
                          "(0 allowed).");
        prm.declare_entry(
          "Crank hole radius",
          "auto",
          parameters::OrAuto(Double(0)),
          "Radius of each crank-shaft hole [mm], > 0; the holes must lie "
          "between the bore and the root circle and must not overlap. auto: "
          "15 mm x (rp - e - rrp) / 125.170 mm (15 mm for the seed).");
        prm.declare_entry(
          "Crank hole circle radius",
          "auto",
          parameters::OrAuto(Double(0)),
          "Radius of the circle through the crank-hole centres [mm], "
          "between Bore radius + Crank hole radius and the root radius - "
          "Crank hole radius. auto: 65 mm x (rp - e - rrp) / 125.170 mm "
          "(65 mm for the seed).");
        prm.declare_entry("Axial gap between discs",
                          "2",
                          Double(0),
                          "Axial gap between the two discs of a 3D scene "
                          "[mm].");
        prm.declare_entry(
          "Housing wall thickness",
          "auto",
          parameters::OrAuto(Double(0)),
          "Radial wall thickness of the pin housing outside the pin circle "
          "[mm], > 1.5 rrp; the housing ring spans rp to rp + this, with a "
          "groove of radius rrp per pin. auto: 15 mm x rp / 130.370 mm, at "
          "least 2.5 rrp (15 mm for the seed).");
      }
      prm.leave_subsection();
    }



    void
    GeometryParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      {
        n_pins                 = prm.get_integer("Number of pins");
        pin_radius             = prm.get_double("Pin radius");
        eccentricity           = prm.get_double("Eccentricity");
        shortening_coefficient = prm.get_double("Shortening coefficient");
        tooth_width            = prm.get_double("Tooth width");
        delta_pin_circle_radius =
          prm.get_double("Pin circle radius modification");
        delta_pin_radius = prm.get_double("Pin radius modification");
        rotation_modification_rad =
          prm.get_double("Rotation modification") * pi / 180.;
        n_crank_holes = prm.get_integer("Number of crank holes");
        axial_gap     = prm.get_double("Axial gap between discs");
        // An auto entry is flagged here and sized by apply_auto_sizes().
        const auto read = [&prm](const std::string &name, double &value) {
          const std::string text = prm.get(name);
          if (parameters::is_auto(text))
            return true;
          value = dealii::Utilities::string_to_double(text);
          return false;
        };
        double zc             = n_teeth;
        automatic.n_teeth     = read("Number of cycloid teeth", zc);
        n_teeth               = static_cast<unsigned int>(zc);
        automatic.bore_radius = read("Bore radius", bore_radius);
        automatic.crank_hole_radius =
          read("Crank hole radius", crank_hole_radius);
        automatic.crank_hole_circle_radius =
          read("Crank hole circle radius", crank_hole_circle_radius);
        automatic.housing_thickness =
          read("Housing wall thickness", housing_thickness);
      }
      prm.leave_subsection();
      apply_auto_sizes();
    }



    void
    GeometryParameters::apply_auto_sizes()
    {
      // The seed's tooth geometry, the reference of the scaling. Both
      // radii are computed by the same expressions as for the parameters,
      // so the ratios are exactly 1 for the seed.
      const auto   pin_circle = [](const double e,
                                 const double z,
                                 const double k1) { return e * z / k1; };
      const double seed_rp    = pin_circle(2.2, 40, 0.675);
      const double seed_root  = seed_rp - 2.2 - 3.0;
      const double rp =
        pin_circle(eccentricity, n_pins, shortening_coefficient);
      const double root_scale = (rp - eccentricity - pin_radius) / seed_root;
      if (automatic.n_teeth)
        n_teeth = n_pins - 1;
      if (automatic.bore_radius)
        bore_radius = 25. * root_scale;
      if (automatic.crank_hole_radius)
        crank_hole_radius = 15. * root_scale;
      if (automatic.crank_hole_circle_radius)
        crank_hole_circle_radius = 65. * root_scale;
      if (automatic.housing_thickness)
        housing_thickness = std::max(15. * (rp / seed_rp), 2.5 * pin_radius);
    }



    bool
    GeometryParameters::left_at_default(const std::string &name) const
    {
      return set_in_file.has_value() && set_in_file->count(name) == 0;
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
      /** "Geometry/@p name", with what kind of default its value is if the
       * file does not set it ("(auto, the default)" for an auto entry
       * @p is_auto). */
      std::string
      entry(const GeometryParameters &prm,
            const std::string        &name,
            const bool                is_auto = false)
      {
        return "Geometry/" + name +
               (is_auto                   ? " (auto, the default)" :
                prm.left_at_default(name) ? " (the default, not set in "
                                            "the parameter file)" :
                                            "");
      }



      /** @p x [mm] rounded to 0.01 mm towards the inside of a bound:
       * down for an upper bound (@p upper), up for a lower one. */
      std::string
      mm(const double x, const bool upper)
      {
        const double r =
          (upper ? std::floor(x * 100.) : std::ceil(x * 100.)) / 100.;
        std::ostringstream s;
        s << r << " mm";
        return s.str();
      }



      /** @p x [mm] for a message. */
      std::string
      mm(const double x)
      {
        std::ostringstream s;
        s << std::setprecision(6) << x << " mm";
        return s.str();
      }



      /** @p prm with every auto entry at auto: the sizes that fit its
       * tooth geometry. */
      GeometryParameters
      auto_sizes(const GeometryParameters &prm)
      {
        GeometryParameters a = prm;
        a.automatic          = {true, true, true, true, true};
        a.apply_auto_sizes();
        return a;
      }



      /** Throw naming Geometry/@p name unless @p value is positive. */
      void
      require_positive(const GeometryParameters &prm,
                       const double              value,
                       const char               *name,
                       const bool                is_auto = false)
      {
        AssertThrow(value > 0,
                    dealii::ExcMessage(entry(prm, name, is_auto) +
                                       " must be positive, got " +
                                       std::to_string(value) + "."));
      }



      /** Positive pin radius, eccentricity, tooth width and bore radius;
       * K1 in (0, 1); zc = zp - 1. Throws dealii::ExcMessage. */
      void
      check_inputs(const GeometryParameters &prm)
      {
        using dealii::ExcMessage;
        require_positive(prm, prm.pin_radius, "Pin radius");
        require_positive(prm, prm.eccentricity, "Eccentricity");
        require_positive(prm, prm.tooth_width, "Tooth width");
        AssertThrow(prm.shortening_coefficient > 0 &&
                      prm.shortening_coefficient < 1,
                    ExcMessage(entry(prm, "Shortening coefficient") +
                               " K1 must lie in (0, 1), got " +
                               std::to_string(prm.shortening_coefficient) +
                               "."));
        require_positive(prm,
                         prm.bore_radius,
                         "Bore radius",
                         prm.automatic.bore_radius);
        AssertThrow(prm.n_teeth + 1 == prm.n_pins,
                    ExcMessage(entry(prm, "Number of cycloid teeth") +
                               " must equal Number of pins - 1 (zc = zp - "
                               "1), got zp = " +
                               std::to_string(prm.n_pins) + ", zc = " +
                               std::to_string(prm.n_teeth) + "; set it to " +
                               std::to_string(prm.n_pins - 1) + " or auto."));
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
                    ExcMessage(entry(prm, "Pin radius") +
                               ": neighbouring pins overlap (2 rrp = " +
                               std::to_string(2. * prm.pin_radius) +
                               " mm >= pin spacing 2 rp sin(pi/zp) = " +
                               std::to_string(chord) +
                               " mm); values that fit: Pin radius < " +
                               mm(0.5 * chord, true) + "."));
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
        const double least = 1.5 * prm.pin_radius;
        AssertThrow(prm.housing_thickness > least,
                    dealii::ExcMessage(
                      entry(prm,
                            "Housing wall thickness",
                            prm.automatic.housing_thickness) +
                      " must exceed 1.5 Pin radius = " + mm(least) +
                      " so that the grooves leave a wall, got " +
                      mm(prm.housing_thickness) +
                      "; values that fit: Housing wall thickness > " +
                      mm(least, false) + " (auto gives " +
                      mm(auto_sizes(prm).housing_thickness) + ")."));
      }



      /** The crank holes that fit between the bore and the root circle
       * @p root of @p prm, as the end of a message: the largest hole
       * radius, and the circle radii that fit for the present radius (or,
       * if that is too large, for three quarters of the largest). */
      std::string
      fitting_crank_holes(const GeometryParameters &prm, const double root)
      {
        const unsigned int n  = prm.n_crank_holes;
        const double       rb = prm.bore_radius;
        // Between bore and root: r < (root - rb) / 2. Apart from each
        // other: r < c sin(pi/n), most room on the largest circle
        // c = root - r, so r < root s / (1 + s).
        const double s = n > 1 ? std::sin(pi / n) : 1.;
        const double r_max =
          std::min(0.5 * (root - rb), n > 1 ? root * s / (1. + s) : root);
        if (r_max <= 0)
          return "none: Bore radius = " + mm(rb) +
                 " leaves no room inside the root radius " + mm(root) +
                 "; reduce Bore radius or set Number of crank holes = 0.";
        const double r =
          prm.crank_hole_radius < r_max ? prm.crank_hole_radius : 0.75 * r_max;
        const double       c_lo = std::max(rb + r, n > 1 ? r / s : 0.);
        const double       c_hi = root - r;
        std::ostringstream text;
        text << "Crank hole radius < " << mm(r_max, true)
             << " (with Bore radius = " << mm(rb)
             << "); Crank hole radius = " << mm(r)
             << " on a Crank hole circle radius of " << mm(c_lo, false)
             << " to " << mm(c_hi, true) << ".";
        return text.str();
      }



      /** The crank holes of @p prm fit between the bore and the root
       * circle @p root and do not overlap. Throws dealii::ExcMessage. */
      void
      check_crank_holes(const GeometryParameters &prm, const double root)
      {
        const auto  &a  = prm.automatic;
        const double r  = prm.crank_hole_radius;
        const double c  = prm.crank_hole_circle_radius;
        const double rb = prm.bore_radius;
        require_positive(prm, r, "Crank hole radius", a.crank_hole_radius);
        require_positive(prm,
                         c,
                         "Crank hole circle radius",
                         a.crank_hole_circle_radius);
        const unsigned int n = prm.n_crank_holes;
        const std::string  problem =
          !(c - r > rb) ?
             "cut into the bore (" + entry(prm, "Bore radius", a.bore_radius) +
              " = " + mm(rb) + ")" :
           !(c + r < root) ?
             "cut the tooth root (root radius " + mm(root) + ")" :
           n > 1 && !(r < c * std::sin(pi / n)) ?
             "overlap: neighbouring crank holes cut into each "
             "other" :
             "";
        if (problem.empty())
          return;
        const bool is_auto = a.crank_hole_radius || a.crank_hole_circle_radius;
        std::ostringstream msg;
        msg << "Geometry/Crank hole radius and Crank hole circle radius: "
            << (is_auto ? "the default (auto) crank holes" : "the crank holes")
            << " (radius " << mm(r) << (a.crank_hole_radius ? ", auto" : "")
            << ", on a circle of " << mm(c)
            << (a.crank_hole_circle_radius ? ", auto" : "") << ") " << problem
            << (is_auto ? "; they do not fit this reducer" : "")
            << ". Values that fit: " << fitting_crank_holes(prm, root);
        AssertThrow(false, dealii::ExcMessage(msg.str()));
      }



      /** Bore and crank holes fit inside the root circle @p root and do
       * not cut into each other. Throws dealii::ExcMessage. */
      void
      check_holes(const GeometryParameters &prm, const double root)
      {
        const bool is_auto = prm.automatic.bore_radius;
        AssertThrow(
          prm.bore_radius < root,
          dealii::ExcMessage(
            entry(prm, "Bore radius", is_auto) + " = " + mm(prm.bore_radius) +
            " does not fit inside the root radius " + mm(root) +
            (is_auto ? "; the auto bore does not fit this reducer" : "") +
            ". Values that fit: Bore radius < " + mm(root, true) +
            (is_auto ? std::string() :
                       " (auto: " + mm(auto_sizes(prm).bore_radius) + ")") +
            "."));
        if (prm.n_crank_holes > 0)
          check_crank_holes(prm, root);
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

// CycloidGeometry::validate(): the checks of a stage that cannot be made
// or cannot carry load, each message naming the entries to change and
// the values that fit (the exact curve: cycloid_geometry.cc).

#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>

#include <cycloid/geometry/cycloid_geometry.h>

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
      check_rest_clearance(const DiscProfile        &g,
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



    namespace
    {
      /** Throw naming Geometry/@p name unless @p value [mm] lies in
       * [@p lo, @p hi]; suggest the unit it was probably typed in. */
      void
      require_plausible(const std::string &name,
                        const double       value,
                        const double       lo,
                        const double       hi)
      {
        if (value >= lo && value <= hi)
          return;
        std::ostringstream msg;
        msg << "Geometry/" << name << " = " << value
            << " mm is far outside any cycloid reducer (" << lo << " to " << hi
            << " mm). Lengths are in mm";
        if (value * 1000. >= lo && value * 1000. <= hi)
          msg << ": did you mean " << value * 1000. << " mm (" << value
              << " m)?";
        else if (value / 1000. >= lo && value / 1000. <= hi)
          msg << ": did you mean " << value / 1000. << " mm (" << value
              << " um)?";
        else
          msg << ".";
        AssertThrow(false, dealii::ExcMessage(msg.str()));
      }
    } // namespace



    void
    GeometryParameters::check_plausible_lengths() const
    {
      // Generous bands around the reducers there are (RV reducers have
      // pins of 1.5 to 15 mm radius on pin circles of 30 to 400 mm): they
      // only catch a unit slip of a factor 1000.
      require_plausible("Pin radius", pin_radius, 0.1, 100.);
      require_plausible("Eccentricity", eccentricity, 0.05, 100.);
      require_plausible("Tooth width", tooth_width, 0.5, 1000.);
      if (shortening_coefficient > 0 && shortening_coefficient < 1)
        {
          const double rp = eccentricity * n_pins / shortening_coefficient;
          AssertThrow(rp >= 2. && rp <= 5000.,
                      dealii::ExcMessage(
                        "the pin circle radius rp = e zp / K1 = " +
                        std::to_string(rp) +
                        " mm (from Geometry/Eccentricity, Number of pins "
                        "and Shortening coefficient) is far outside any "
                        "cycloid reducer (2 to 5000 mm). Lengths are in "
                        "mm."));
        }
      for (const auto &[name, value] :
           {std::pair<const char *, double>{"Pin circle radius modification",
                                            delta_pin_circle_radius},
            {"Pin radius modification", delta_pin_radius}})
        require_plausible(name, value, -1., 1.);
    }



    void
    CycloidGeometry::validate() const
    {
      // Cheap parameter checks first, so that the message names the input
      // before a derived quantity (undercut, clearance) trips over it.
      check_inputs(prm);
      for (const DiscProfile &p : profiles)
        check_modifications(p.generating_radius(),
                            p.modified_shortening_coefficient());
      check_pin_spacing(prm, rp, zp);
      for (const DiscProfile &p : profiles)
        check_undercut(p.undercut_margin(), p.generating_radius());
      for (const DiscProfile &p : profiles)
        check_rest_clearance(p, prm, rp, zc, i_h);
      check_housing(prm);
      check_holes(prm, root_radius());
    }
  } // namespace geometry
} // namespace cycloid

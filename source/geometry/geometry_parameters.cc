// GeometryParameters: subsection Geometry of the parameter file, and the
// auto sizes derived from the tooth geometry.

#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>

#include <cycloid/geometry/geometry_parameters.h>
#include <cycloid/parameters/or_auto.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace cycloid
{
  namespace geometry
  {
    namespace
    {
      constexpr double pi = dealii::numbers::PI;
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
          "circle radius rp follows from it, unless Pin circle radius is "
          "given.");
        prm.declare_entry(
          "Pin circle radius",
          "auto",
          parameters::OrAuto(Double(0)),
          "Pin circle radius rp [mm]: the radius of the circle through the "
          "pin centres. auto: e zp / K1 from the Shortening coefficient. A "
          "value sets K1 = e zp / rp instead (then rp stays where the "
          "drawing has it when e changes); given together with a "
          "Shortening coefficient that disagrees, it is an error.");
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
        const std::string rp_text = prm.get("Pin circle radius");
        given_pin_circle_radius =
          parameters::is_auto(rp_text) ?
            0. :
            dealii::Utilities::string_to_double(rp_text);
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
      if (given_pin_circle_radius > 0)
        {
          const double ezp = eccentricity * n_pins;
          AssertThrow(given_pin_circle_radius > ezp,
                      dealii::ExcMessage(
                        "Geometry/Pin circle radius = " +
                        dealii::Utilities::to_string(given_pin_circle_radius) +
                        " mm must exceed e zp = " +
                        dealii::Utilities::to_string(ezp) +
                        " mm (Eccentricity times Number of pins), so that "
                        "K1 = e zp / rp < 1."));
          shortening_coefficient = ezp / given_pin_circle_radius;
          // The K1 the run uses, so that parameters.prm (rp and this K1)
          // repeats the run.
          std::ostringstream k1;
          k1 << std::setprecision(17) << shortening_coefficient;
          prm.enter_subsection("Geometry");
          prm.set("Shortening coefficient", k1.str());
          prm.leave_subsection();
        }
      check_plausible_lengths();
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
  } // namespace geometry
} // namespace cycloid

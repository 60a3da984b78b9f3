#ifndef cycloid_geometry_geometry_parameters_h
#define cycloid_geometry_geometry_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <cycloid/geometry/deviation_data.h>

#include <optional>
#include <set>
#include <string>
#include <vector>

namespace cycloid
{
  namespace geometry
  {
    /**
     * @brief Geometry parameters of the cycloid-pin stage (subsection
     * `Geometry` of the parameter file). Lengths in mm, angles in degrees
     * in the file, radians in the members whose name ends in `_rad`.
     *
     * The number of cycloid teeth, the bore, the crank holes and the
     * housing wall default to `auto`: sizes derived from the tooth geometry
     * (apply_auto_sizes()), so that a file that sets only the tooth
     * geometry of another reducer describes a disc that fits. For the seed
     * geometry the auto sizes are exactly the member defaults below.
     */
    struct GeometryParameters
    {
      /** Which entries were `auto` in the parameter file (their members
       * hold the derived values). A value given in code counts as set. */
      struct Automatic
      {
        bool n_teeth                  = false; ///< Number of cycloid teeth.
        bool bore_radius              = false; ///< Bore radius.
        bool crank_hole_radius        = false; ///< Crank hole radius.
        bool crank_hole_circle_radius = false; ///< Crank hole circle radius.
        bool housing_thickness        = false; ///< Housing wall thickness.
      };


      /** Number of pins zp. */
      unsigned int n_pins = 40;
      /** Number of cycloid teeth zc; must equal zp - 1. */
      unsigned int n_teeth = 39;
      /** Pin radius rrp [mm]. */
      double pin_radius = 3.0;
      /** Eccentricity e [mm]. */
      double eccentricity = 2.2;
      /** Shortening coefficient K1 = e zp / rp (0 < K1 < 1). */
      double shortening_coefficient = 0.675;
      /** Tooth (disc) width b [mm]. */
      double tooth_width = 16.0;
      /** Pin circle radius modification Delta rp [mm]. */
      double delta_pin_circle_radius = 0.0;
      /** Pin radius modification Delta rrp [mm]. */
      double delta_pin_radius = 0.0;
      /** Rotation modification delta [rad]. */
      double rotation_modification_rad = 0.0;
      /** Radius of the central bore [mm]. */
      double bore_radius = 25.0;
      /** Number of crank-shaft holes in each disc (0 allowed). */
      unsigned int n_crank_holes = 3;
      /** Radius of each crank hole [mm]. */
      double crank_hole_radius = 15.0;
      /** Radius of the circle through the crank-hole centres [mm]. */
      double crank_hole_circle_radius = 65.0;
      /** Axial gap between the two discs of a 3D scene [mm]. */
      double axial_gap = 2.0;
      /** Radial wall thickness of the pin housing outside the pin circle
       * [mm]: the housing ring spans rp ... rp + this. */
      double housing_thickness = 15.0;

      /** Geometry/Pin circle radius as the file gives it [mm], or 0 for
       * auto: then the shortening coefficient sets rp = e zp / K1; else
       * it sets K1 = e zp / rp (parse_parameters()). */
      double given_pin_circle_radius = 0;

      /** The entries that were `auto`. */
      Automatic automatic;
      /**
       * The entries of subsection `Geometry` that the parameter file sets
       * (app::AllParameters::read() fills it); empty optional when unknown
       * (parameters made in code). An error about an entry the file does
       * not set says that the value is a default.
       */
      std::optional<std::set<std::string>> set_in_file;
      /** The pins' manufacturing deviations (subsection `Deviations`;
       * empty: every pin as drawn). CycloidGeometry(prm) honours them. */
      std::vector<PinDeviation> pin_deviations;
      /** The discs' manufacturing deviations (empty: as drawn). */
      std::vector<DiscDeviation> disc_deviations;
      /** Check the drawing (profile, undercut, clearance at rest, housing,
       * holes) when a CycloidGeometry is built. A tolerance study's
       * samples turn it off: their drawing is the mean stage's, checked
       * once, the deviations move it by a few um, and a sample that cannot
       * be assembled shows as a negative clearance of its pins at rest
       * (analytic::StageModel::unloaded_pins() throws); the check would
       * cost ten times the sample's own work. */
      bool check_drawing = true;

      /** Declare the entries of subsection `Geometry`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsection `Geometry`; throws with the entry's name on a bad
       * value that the pattern alone cannot catch. */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /**
       * Set the members flagged in #automatic from the tooth geometry:
       * zc = zp - 1; bore, crank-hole radius and crank-hole circle radius
       * are the seed's 25, 15 and 65 mm scaled by the ratio of the nominal
       * root radius rp - e - rrp (rp = e zp / K1) to the seed's
       * (125.170 mm); the housing wall is the seed's 15 mm scaled by
       * rp / 130.370 mm, at least 2.5 rrp. The ratios are 1 for the seed
       * geometry, so its auto sizes are exactly 25, 15, 65 and 15 mm; for
       * any other reducer the holes keep the seed's proportions to the
       * root circle (bore 0.200 root radii, ligaments bore to holes 0.200
       * and holes to root 0.361 root radii) and pass CycloidGeometry's
       * checks.
       */
      void
      apply_auto_sizes();

      /**
       * Throw if a length lies far outside any cycloid reducer (a pin
       * radius below 0.1 mm or above 100 mm, a pin circle radius below
       * 2 mm or above 5 m, ...), naming the entry and, where the value
       * would be plausible in metres or micrometres, the millimetres it
       * probably means: a value typed in the wrong unit is caught before
       * a check further on names an entry the user never set. Called by
       * parse_parameters(); ranges in source/geometry/validation.cc.
       */
      void
      check_plausible_lengths() const;

      /** Whether the parameter file is known to leave entry @p name of
       * subsection `Geometry` at its default. */
      bool
      left_at_default(const std::string &name) const;
    };
  } // namespace geometry
} // namespace cycloid

#endif

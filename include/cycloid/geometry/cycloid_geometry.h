#ifndef cycloid_geometry_cycloid_geometry_h
#define cycloid_geometry_cycloid_geometry_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <optional>
#include <set>
#include <string>
#include <vector>

namespace cycloid
{
  namespace geometry
  {
    using dealii::Point;
    using dealii::Tensor;

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

      /** The entries that were `auto`. */
      Automatic automatic;
      /**
       * The entries of subsection `Geometry` that the parameter file sets
       * (app::AllParameters::read() fills it); empty optional when unknown
       * (parameters made in code). An error about an entry the file does
       * not set says that the value is a default.
       */
      std::optional<std::set<std::string>> set_in_file;

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

      /** Whether the parameter file is known to leave entry @p name of
       * subsection `Geometry` at its default. */
      bool
      left_at_default(const std::string &name) const;
    };

    /**
     * @brief A point of the (modified) cycloid profile with its local
     * differential geometry, in the disc frame (disc centre at the origin).
     */
    struct ProfilePoint
    {
      /** Profile parameter phi [rad] (the generating phase). */
      double phi;
      /** Position [mm]. */
      Point<2> point;
      /** Derivative d point / d phi [mm/rad]. */
      Tensor<1, 2> derivative;
      /** Unit normal pointing out of the disc (towards the pins). */
      Tensor<1, 2> normal;
      /**
       * Signed radius of curvature [mm]: positive where the profile is
       * concave (centre of curvature outside the disc, the tooth root),
       * negative where it is convex (the tooth tip). Infinite at an
       * inflection point.
       */
      double curvature_radius;
    };

    /**
     * @brief Contact geometry of one pin against one disc in the assembled,
     * unloaded stage (housing frame, housing centre at the origin).
     */
    struct PinContact
    {
      /** Disc index (0 or 1). */
      unsigned int disc;
      /** Pin index j, pin centre at angle 2 pi j / zp. */
      unsigned int pin;
      /** Initial clearance along the contact normal [mm]; negative means
       * overlap. */
      double clearance;
      /** Closest point of the disc profile to the pin centre [mm]. */
      Point<2> contact_point;
      /** Unit contact normal, pointing from the disc towards the pin. */
      Tensor<1, 2> normal;
      /**
       * Signed moment arm about the disc centre [mm]: the z-component of
       * (contact point - disc centre) x normal. A pin with a positive arm
       * resists a positive (counter-clockwise) torque on the disc; a
       * counter-clockwise rotation beta of the disc closes its clearance by
       * beta * arm.
       */
      double arm;
      /** Profile parameter of the contact point, reduced to [0, 2 pi):
       * 0 at the tooth root, pi at the tooth tip. */
      double phase;
      /** Signed curvature radius of the profile at the contact point [mm]
       * (see ProfilePoint::curvature_radius). */
      double curvature_radius;
      /** Disc centre in the housing frame [mm]. */
      Point<2> disc_centre;
    };

    /**
     * @brief Exact geometry of the cycloid-pin stage: the standard and
     * modified cycloid profile as a parametric curve with tangents, normals
     * and curvature, the kinematic assembly of one or two discs at a crank
     * angle, and per-pin contact quantities found by a closest-point search.
     *
     * The profile in the disc frame (doc/design-basis.md §2.1, seed eq. with
     * `phi^-1(K1,phi)` read as S^-1/2) is
     * @f[
     *   P(\phi) = R e^{i\alpha} - e\,e^{-i\gamma}
     *             - r\,\frac{u(\phi)}{\sqrt{S}}, \quad
     *   u = e^{i\alpha} - K e^{-i\gamma},\quad |u|^2 = S = 1 + K^2 - 2K\cos\phi
     * @f]
     * with @f$\alpha = (1-i_H)\phi@f$, @f$\gamma = i_H\phi@f$,
     * @f$R = r_p+\Delta r_p@f$, @f$r = r_{rp}+\Delta r_{rp}@f$,
     * @f$K = e z_p/R@f$, and the whole curve turned by @f$-\delta@f$ (the
     * seed's sign). The first two terms are the pin-centre curve (an
     * epitrochoid) and @f$u/\sqrt S@f$ is its unit outward normal, so the
     * profile is the inner parallel curve of the pin-centre curve at
     * distance r. One tooth spans 2 pi in phi; the closed profile spans
     * [0, 2 pi zc).
     *
     * Assembly (doc/design-basis.md §2.2): pin j at rp (cos 2 pi j/zp, sin 2 pi
     * j/zp); disc 0 centred at e (cos psi, sin psi) and turned by -psi/zc; disc
     * 1 at crank angle psi + pi.
     */
    class CycloidGeometry
    {
    public:
      /** Build from parameters; validates them and throws
       * dealii::ExcMessage naming the offending parameter. */
      explicit CycloidGeometry(const GeometryParameters &parameters);

      /** @name Derived quantities */
      /** @{ */
      /** The parameters this geometry was built from. */
      const GeometryParameters &
      parameters() const
      {
        return prm;
      }
      /** Nominal pin-circle radius rp = e zp / K1 [mm]. */
      double
      pin_circle_radius() const
      {
        return rp;
      }
      /** Transmission ratio iH = zp / zc. */
      double
      transmission_ratio() const
      {
        return i_h;
      }
      /** Shortening coefficient of the modified profile K = e zp/(rp+Delta rp).
       */
      double
      modified_shortening_coefficient() const
      {
        return k_mod;
      }
      /** Smallest radius of the modified profile (tooth root) [mm]. */
      double
      root_radius() const;
      /** Largest radius of the modified profile (tooth tip) [mm]. */
      double
      tip_radius() const;
      /** Crank angle period of the meshing, 2 pi / zp [rad]. */
      double
      mesh_period() const;
      /** @} */

      /** @name Profile in the disc frame */
      /** @{ */
      /** Point, derivative, outward normal and curvature at parameter phi. */
      ProfilePoint
      profile(const double phi) const;

      /** Second derivative d^2 P / d phi^2 [mm/rad^2]. */
      Tensor<1, 2>
      profile_second_derivative(const double phi) const;

      /**
       * Closest point of the profile to @p q (disc frame) by a real search:
       * coarse sampling of a window of one and a half teeth around the polar
       * angle of q, then a safeguarded Newton iteration on
       * d|P(phi)-q|^2/dphi = 0. Does not use any kinematic knowledge of
       * where q came from.
       */
      ProfilePoint
      closest_point(const Point<2> &q) const;

      /**
       * Signed distance of @p q from the profile [mm]: positive outside the
       * disc, negative inside; @p closest receives the closest point.
       */
      double
      signed_distance(const Point<2> &q, ProfilePoint *closest = nullptr) const;
      /** @} */

      /** @name Assembly in the housing frame */
      /** @{ */
      /** Centre of crank hole @p k in the disc frame [mm] (hole k at angle
       * 2 pi k / Number of crank holes). */
      Point<2>
      crank_hole_centre(const unsigned int k) const;

      /** Centre of crank hole @p k of disc @p disc at crank angle @p psi,
       * housing frame [mm]. */
      Point<2>
      crank_hole_centre(const unsigned int disc,
                        const unsigned int k,
                        const double       psi) const;

      /** Centre of pin @p j [mm]. */
      Point<2>
      pin_centre(const unsigned int j) const;

      /** Crank angle [rad] that places disc @p disc when the crank is at
       * @p psi (disc 1 runs half a turn ahead). */
      static double
      disc_crank_angle(const unsigned int disc, const double psi);

      /** Centre of disc @p disc at crank angle @p psi [mm]. */
      Point<2>
      disc_centre(const unsigned int disc, const double psi) const;

      /** Rotation angle of disc @p disc at crank angle @p psi [rad]. */
      double
      disc_rotation(const unsigned int disc, const double psi) const;

      /** Map a disc-frame point to the housing frame. */
      Point<2>
      to_housing(const unsigned int disc,
                 const double       psi,
                 const Point<2>    &p_disc) const;

      /** Map a housing-frame point to the disc frame. */
      Point<2>
      to_disc(const unsigned int disc,
              const double       psi,
              const Point<2>    &q_housing) const;

      /** Contact quantities of pin @p j against disc @p disc at crank
       * angle @p psi, from a closest-point search. */
      PinContact
      pin_contact(const unsigned int disc,
                  const unsigned int j,
                  const double       psi) const;

      /** pin_contact() for every pin of one disc. */
      std::vector<PinContact>
      pin_contacts(const unsigned int disc, const double psi) const;

      /** Pitch point of disc @p disc: on the line through the housing and
       * disc centres, at distance e zp from the housing centre [mm]. */
      Point<2>
      pitch_point(const unsigned int disc, const double psi) const;
      /** @} */

      /** @name Closed forms (used for checks and by the seed's model) */
      /** @{ */
      /** S(phi) = 1 + K^2 - 2 K cos phi with the modified K. */
      double
      s_function(const double phi) const;

      /** Curvature radius of the standard profile from the textbook closed
       * form rho = rp S^{3/2} / (K1 (1+zp) cos phi - (1 + zp K1^2)) + rrp
       * (positive concave); evaluated with the modified R, r and K. */
      double
      closed_form_curvature_radius(const double phi) const;

      /**
       * First-order normal clearance of a pin at generating phase phi due to
       * the modifications Delta rp, Delta rrp (no rotation modification):
       * Delta rrp - Delta rp (1 - K cos phi) / sqrt(S).
       */
      double
      first_order_clearance(const double phi) const;

      /**
       * The seed article's backlash formula
       * Delta(phi) = Delta rrp (1 - sin phi/sqrt S)
       *   - Delta rp (1 - K cos phi - sqrt(1-K^2) sin phi)/sqrt S.
       * It equals first_order_clearance() minus the rigid take-up
       * rotation that closes the clearance of the pin at cos phi = K (see
       * doc/analytic-model.md).
       */
      double
      seed_backlash(const double phi) const;

      /** Moment arm about the disc centre from the closed form
       * l = e zc sin(phi) / sqrt(S) (standard profile). */
      double
      closed_form_arm(const double phi) const;
      /** @} */

      /** Smallest |curvature radius| of the pin-centre curve on its convex
       * part minus the generating radius r [mm]; the profile undercuts
       * (curvature radius passes through zero) when this is <= 0. */
      double
      undercut_margin() const;

    private:
      /** Validate parameters (throws). */
      void
      validate() const;

      /** Unrotated profile point and derivatives (before the turn by
       * -delta). */
      void
      evaluate(const double  phi,
               Tensor<1, 2> &p,
               Tensor<1, 2> &dp,
               Tensor<1, 2> &ddp,
               Tensor<1, 2> &normal) const;

      const GeometryParameters prm;
      const unsigned int       zp;
      const unsigned int       zc;
      const double             rp;
      const double             i_h;
      const double             big_r;
      const double             small_r;
      const double             k_mod;
      const double             delta;
    };
  } // namespace geometry
} // namespace cycloid

#endif

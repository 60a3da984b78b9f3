#ifndef cycloid_geometry_disc_profile_h
#define cycloid_geometry_disc_profile_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <cycloid/geometry/geometry_parameters.h>
#include <cycloid/geometry/stage_layout.h>

namespace cycloid
{
  namespace geometry
  {
    using dealii::Point;
    using dealii::Tensor;

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
     * @brief The exact profile of one disc, as its own modifications made
     * it: a parametric curve with tangents, normals and curvature, the
     * closest point to any point, and the closed forms of the textbook
     * profile.
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
     * The curve is generated with the design's e, zp, rp and rrp and the
     * disc's own Delta rp, Delta rrp and delta (DiscData): a disc placed on
     * an eccentric that differs from e keeps the profile it was ground
     * with.
     */
    class DiscProfile
    {
    public:
      /** The profile of a disc with modifications @p disc of the stage
       * designed by @p prm, whose nominal pin circle radius is @p rp
       * [mm]. */
      DiscProfile(const GeometryParameters &prm,
                  const double              rp,
                  const DiscData           &disc);

      /** Shortening coefficient of the modified profile K = e zp/(rp+Delta
       * rp). */
      double
      modified_shortening_coefficient() const
      {
        return k_mod;
      }
      /** Generating radius r = rrp + Delta rrp [mm]. */
      double
      generating_radius() const
      {
        return small_r;
      }
      /** Smallest radius of the modified profile (tooth root) [mm]. */
      double
      root_radius() const;
      /** Largest radius of the modified profile (tooth tip) [mm]. */
      double
      tip_radius() const;

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
      /** Unrotated profile point and derivatives (before the turn by
       * -delta). */
      void
      evaluate(const double  phi,
               Tensor<1, 2> &p,
               Tensor<1, 2> &dp,
               Tensor<1, 2> &ddp,
               Tensor<1, 2> &normal) const;

      const unsigned int zp;        ///< Number of pins.
      const unsigned int zc;        ///< Number of teeth.
      const double       e;         ///< Generating eccentricity [mm].
      const double       i_h;       ///< zp / zc.
      const double       big_r;     ///< R = rp + Delta rp [mm].
      const double       small_r;   ///< r = rrp + Delta rrp [mm].
      const double       k_mod;     ///< K = e zp / R.
      const double       delta;     ///< Rotation modification [rad].
      const double       delta_rp;  ///< Delta rp [mm].
      const double       delta_rrp; ///< Delta rrp [mm].
    };
  } // namespace geometry
} // namespace cycloid

#endif

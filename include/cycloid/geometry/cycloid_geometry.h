#ifndef cycloid_geometry_cycloid_geometry_h
#define cycloid_geometry_cycloid_geometry_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <cycloid/geometry/disc_profile.h>
#include <cycloid/geometry/geometry_parameters.h>
#include <cycloid/geometry/stage_layout.h>

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
     * @brief Exact geometry of the cycloid-pin stage: the stage as data
     * (StageLayout: every pin and every disc), each disc's profile
     * (DiscProfile), the kinematic assembly of the discs at a crank angle,
     * and per-pin contact quantities found by a closest-point search.
     *
     * Assembly (doc/design-basis.md §2.2): pin j where the layout puts it
     * (nominally rp (cos 2 pi j/zp, sin 2 pi j/zp)); disc d centred at
     * e_d (cos(psi + o_d), sin(psi + o_d)) with its crank offset o_d (0 and
     * pi) and turned by -(psi + o_d)/zc plus its index angle (nominally
     * 0). The profile functions without a disc argument are disc 0's;
     * a layout whose discs have their own modifications is read through
     * disc_profile().
     */
    class CycloidGeometry
    {
    public:
      /** The nominal stage of @p parameters (StageLayout::nominal());
       * validates them and throws dealii::ExcMessage naming the offending
       * parameter. */
      explicit CycloidGeometry(const GeometryParameters &parameters);

      /** The stage designed by @p parameters as @p layout has it: pins and
       * discs where and as they really are. Validates as above. */
      CycloidGeometry(const GeometryParameters &parameters,
                      const StageLayout        &layout);

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
      /** The stage as data: every pin and disc. */
      const StageLayout &
      layout() const
      {
        return stage;
      }
      /** The profile of disc @p disc. */
      const DiscProfile &
      disc_profile(const unsigned int disc) const
      {
        return profiles[disc];
      }
      /** Shortening coefficient of the modified profile K = e zp/(rp+Delta rp)
       * (disc 0). */
      double
      modified_shortening_coefficient() const
      {
        return profiles[0].modified_shortening_coefficient();
      }
      /** Smallest radius of the modified profile (tooth root) [mm] (disc
       * 0). */
      double
      root_radius() const
      {
        return profiles[0].root_radius();
      }
      /** Largest radius of the modified profile (tooth tip) [mm] (disc 0). */
      double
      tip_radius() const
      {
        return profiles[0].tip_radius();
      }
      /** Crank angle period of the meshing, 2 pi / zp [rad]. */
      double
      mesh_period() const;
      /** @} */

      /** @name Profile of disc 0 in the disc frame (DiscProfile) */
      /** @{ */
      /** DiscProfile::profile() of disc 0. */
      ProfilePoint
      profile(const double phi) const
      {
        return profiles[0].profile(phi);
      }

      /** DiscProfile::profile_second_derivative() of disc 0. */
      Tensor<1, 2>
      profile_second_derivative(const double phi) const
      {
        return profiles[0].profile_second_derivative(phi);
      }

      /** DiscProfile::closest_point() of disc 0. */
      ProfilePoint
      closest_point(const Point<2> &q) const
      {
        return profiles[0].closest_point(q);
      }

      /** DiscProfile::signed_distance() of disc 0. */
      double
      signed_distance(const Point<2> &q, ProfilePoint *closest = nullptr) const
      {
        return profiles[0].signed_distance(q, closest);
      }
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

      /** Centre of pin @p j [mm], from the layout. */
      Point<2>
      pin_centre(const unsigned int j) const;

      /** Radius of pin @p j [mm], from the layout. */
      double
      pin_radius(const unsigned int j) const;

      /** Crank angle [rad] that places disc @p disc when the crank is at
       * @p psi (disc 1 runs half a turn ahead: its crank offset). */
      double
      disc_crank_angle(const unsigned int disc, const double psi) const;

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

      /** @name Closed forms of disc 0's profile (DiscProfile) */
      /** @{ */
      /** DiscProfile::s_function() of disc 0. */
      double
      s_function(const double phi) const
      {
        return profiles[0].s_function(phi);
      }
      /** DiscProfile::closed_form_curvature_radius() of disc 0. */
      double
      closed_form_curvature_radius(const double phi) const
      {
        return profiles[0].closed_form_curvature_radius(phi);
      }
      /** DiscProfile::first_order_clearance() of disc 0. */
      double
      first_order_clearance(const double phi) const
      {
        return profiles[0].first_order_clearance(phi);
      }
      /** DiscProfile::seed_backlash() of disc 0. */
      double
      seed_backlash(const double phi) const
      {
        return profiles[0].seed_backlash(phi);
      }
      /** DiscProfile::closed_form_arm() of disc 0. */
      double
      closed_form_arm(const double phi) const
      {
        return profiles[0].closed_form_arm(phi);
      }
      /** DiscProfile::undercut_margin() of disc 0. */
      double
      undercut_margin() const
      {
        return profiles[0].undercut_margin();
      }
      /** @} */

    private:
      /** Validate parameters and profiles (throws). */
      void
      validate() const;

      const GeometryParameters prm;
      /** The pins and discs as they are. */
      const StageLayout stage;
      /** Each disc's profile, disc d at index d. */
      std::vector<DiscProfile> profiles;
      const unsigned int       zp;
      const unsigned int       zc;
      /** Nominal pin circle radius e zp / K1 [mm]. */
      const double rp;
      const double i_h;
    };
  } // namespace geometry
} // namespace cycloid

#endif

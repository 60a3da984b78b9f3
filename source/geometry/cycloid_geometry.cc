// CycloidGeometry: the exact curve of the (modified) profile, closest
// points, placement of the discs and the contact geometry of each pin
// (parameters: geometry_parameters.cc; checks: validation.cc).

#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/geometry/deviations.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace cycloid
{
  namespace geometry
  {
    namespace
    {
      constexpr double pi = dealii::numbers::PI;

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



    CycloidGeometry::CycloidGeometry(const GeometryParameters &parameters)
      : CycloidGeometry(parameters,
                        deviated_layout(parameters,
                                        parameters.pin_deviations,
                                        parameters.disc_deviations))
    {}



    CycloidGeometry::CycloidGeometry(const GeometryParameters &parameters,
                                     const StageLayout        &layout)
      : prm(parameters)
      , stage(layout)
      , zp(parameters.n_pins)
      , zc(parameters.n_teeth)
      , rp(parameters.shortening_coefficient > 0 ?
             parameters.eccentricity * parameters.n_pins /
               parameters.shortening_coefficient :
             0.)
      , i_h(static_cast<double>(parameters.n_pins) /
            std::max(1u, parameters.n_teeth))
    {
      AssertThrow(layout.pins.size() == zp &&
                    layout.discs.size() == StageLayout::n_discs,
                  dealii::ExcMessage(
                    "the stage layout has " +
                    std::to_string(layout.pins.size()) + " pins and " +
                    std::to_string(layout.discs.size()) +
                    " discs; Geometry/Number of pins = " + std::to_string(zp) +
                    " and two discs were expected."));
      for (const DiscData &disc : layout.discs)
        profiles.emplace_back(parameters, rp, disc);
      if (parameters.check_drawing)
        validate();
    }



    double
    CycloidGeometry::mesh_period() const
    {
      return 2. * pi / zp;
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
      AssertIndexRange(j, stage.pins.size());
      return stage.pins[j].centre;
    }



    double
    CycloidGeometry::pin_radius(const unsigned int j) const
    {
      AssertIndexRange(j, stage.pins.size());
      return stage.pins[j].radius;
    }



    double
    CycloidGeometry::disc_crank_angle(const unsigned int disc,
                                      const double       psi) const
    {
      return psi + stage.discs[disc].crank_offset;
    }



    Point<2>
    CycloidGeometry::disc_centre(const unsigned int disc,
                                 const double       psi) const
    {
      const double a = disc_crank_angle(disc, psi);
      const double e = stage.discs[disc].eccentricity;
      return Point<2>(e * std::cos(a), e * std::sin(a));
    }



    double
    CycloidGeometry::disc_rotation(const unsigned int disc,
                                   const double       psi) const
    {
      return -disc_crank_angle(disc, psi) / zc + stage.discs[disc].index_angle;
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
      const double   d     = profiles[disc].signed_distance(q, &cp);
      const double   angle = disc_rotation(disc, psi);
      PinContact     result;
      result.disc          = disc;
      result.pin           = j;
      result.clearance     = d - pin_radius(j);
      result.contact_point = to_housing(disc, psi, cp.point);
      result.normal        = rotate(cp.normal, angle);
      result.arm           = cross(Tensor<1, 2>(cp.point), cp.normal);
      // A pin on the line of the eccentricity (tooth tip or root) has no
      // arm by symmetry; the closest point leaves round-off there (9.7e-14
      // mm on a 30-pin stage), which a reader who misses the exponent
      // takes for 9.7 mm.
      if (std::abs(result.arm) < 1e-12 * rp)
        result.arm = 0;
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
      const double d = stage.discs[disc].eccentricity * zp;
      return Point<2>(d * std::cos(a), d * std::sin(a));
    }



  } // namespace geometry
} // namespace cycloid

#ifndef cycloid_profile_outline_h
#define cycloid_profile_outline_h

#include <deal.II/base/point.h>

#include <cycloid/geometry/cycloid_geometry.h>

#include <vector>

namespace cycloid
{
  namespace profile
  {
    /**
     * @brief A hole of the disc (bore or crank hole) in the disc frame.
     */
    struct Circle
    {
      /** Centre in the disc frame [mm]. */
      dealii::Point<2> centre;
      /** Radius [mm]. */
      double radius;
    };

    /**
     * @brief The outline of one disc in its own frame (disc centre at the
     * origin, unrotated): the modified profile as a closed polyline whose
     * vertices lie on the exact curve, and the holes.
     */
    struct DiscOutline
    {
      /**
       * Profile parameter of each vertex [rad]: 0 for the first vertex
       * (a tooth root), then decreasing towards -2 pi zc, which closes the
       * curve. Decreasing phi runs counter-clockwise (the profile's polar
       * angle is about -phi/zc - delta).
       */
      std::vector<double> phi;
      /** The vertices [mm], counter-clockwise; the first is not repeated. */
      std::vector<dealii::Point<2>> vertices;
      /** The chord tolerance the polyline was sampled to [mm]. */
      double chord_tolerance = 0;
      /** The largest distance of a chord from the exact curve [mm]. */
      double max_chord_deviation = 0;
      /** The bore (first) and the crank holes (hole k at angle
       * 2 pi k / Number of crank holes). */
      std::vector<Circle> holes;
    };

    /**
     * Largest distance of the profile arc between the parameters
     * @p phi_a and @p phi_b from the chord joining its ends [mm]: sampled
     * at the quarter points and refined at the vertex of the parabola
     * through them, which is where a short smooth arc is farthest from its
     * chord.
     */
    double
    chord_deviation(const geometry::CycloidGeometry &geometry,
                    const double                     phi_a,
                    const double                     phi_b);

    /**
     * Sample the modified profile of @p geometry adaptively so that every
     * chord deviates from the exact curve by at most @p tolerance [mm].
     * Each step starts from the a-priori chord length sqrt(8 |rho| tol)
     * of the local curvature radius rho and is halved until
     * chord_deviation() meets the tolerance. Every vertex is a point
     * CycloidGeometry::profile() of the exact curve.
     */
    DiscOutline
    sample_outline(const geometry::CycloidGeometry &geometry,
                   const double                     tolerance);
  } // namespace profile
} // namespace cycloid

#endif

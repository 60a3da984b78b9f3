#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>

#include <cycloid/profile/outline.h>

#include <algorithm>
#include <cmath>

namespace cycloid
{
  namespace profile
  {
    namespace
    {
      using dealii::Point;
      using dealii::Tensor;

      /** Distance of @p q from the segment from @p a to @p b [mm]. */
      double
      distance_to_segment(const Point<2> &q,
                          const Point<2> &a,
                          const Point<2> &b)
      {
        const Tensor<1, 2> ab = b - a;
        const double       l2 = ab * ab;
        const double t = l2 > 0 ? std::clamp(((q - a) * ab) / l2, 0., 1.) : 0.;
        return (q - (a + t * ab)).norm();
      }

      /** The a-priori parameter step at @p phi: the chord of length
       * sqrt(8 |rho| tol) deviates by tol from a circle of radius rho;
       * 0.9 of it so that most steps pass at once. At most @p cap (an
       * inflection point has an infinite rho). */
      double
      a_priori_step(const geometry::CycloidGeometry &geometry,
                    const double                     phi,
                    const double                     tolerance,
                    const double                     cap)
      {
        const geometry::ProfilePoint p   = geometry.profile(phi);
        const double                 rho = std::abs(p.curvature_radius);
        const double chord = 0.9 * std::sqrt(8. * rho * tolerance);
        return std::min(cap, chord / p.derivative.norm());
      }
    } // namespace



    double
    chord_deviation(const geometry::CycloidGeometry &geometry,
                    const double                     phi_a,
                    const double                     phi_b)
    {
      const Point<2> a  = geometry.profile(phi_a).point;
      const Point<2> b  = geometry.profile(phi_b).point;
      const auto     at = [&](const double s) {
        return distance_to_segment(
          geometry.profile(phi_a + s * (phi_b - phi_a)).point, a, b);
      };
      const double d1 = at(0.25), d2 = at(0.5), d3 = at(0.75);
      double       worst = std::max({d1, d2, d3});
      // Vertex of the parabola through the three samples (concave when
      // d2 dominates): the distance of a short arc from its chord is
      // nearly quadratic in the parameter.
      const double curvature = d1 - 2. * d2 + d3;
      if (curvature < 0)
        {
          const double s =
            std::clamp(0.5 + 0.25 * 0.5 * (d1 - d3) / curvature, 0., 1.);
          worst = std::max(worst, at(s));
        }
      return worst;
    }



    DiscOutline
    sample_outline(const geometry::CycloidGeometry &geometry,
                   const double                     tolerance)
    {
      AssertThrow(tolerance > 0,
                  dealii::ExcMessage("Profile/Chord tolerance must be "
                                     "positive."));
      const double two_pi = 2. * dealii::numbers::PI;
      const double end    = -two_pi * geometry.parameters().n_teeth;
      // No step beyond 1/16 of a tooth: near an inflection point the
      // a-priori step is unbounded.
      const double cap = two_pi / 16.;

      DiscOutline outline;
      outline.chord_tolerance = tolerance;
      double phi              = 0.;
      while (true)
        {
          outline.phi.push_back(phi);
          outline.vertices.push_back(geometry.profile(phi).point);
          double h = a_priori_step(geometry, phi, tolerance, cap);
          // Land on the closing point rather than leave a sliver.
          const bool last = (phi - end) <= 1.25 * h;
          if (last)
            h = phi - end;
          double deviation = chord_deviation(geometry, phi, phi - h);
          while (deviation > tolerance)
            {
              h /= 2.;
              deviation = chord_deviation(geometry, phi, phi - h);
            }
          outline.max_chord_deviation =
            std::max(outline.max_chord_deviation, deviation);
          if (last && h == phi - end)
            break;
          phi -= h;
        }

      const auto &prm = geometry.parameters();
      outline.holes.push_back({Point<2>(), prm.bore_radius});
      for (unsigned int k = 0; k < prm.n_crank_holes; ++k)
        outline.holes.push_back(
          {geometry.crank_hole_centre(k), prm.crank_hole_radius});
      return outline;
    }
  } // namespace profile
} // namespace cycloid

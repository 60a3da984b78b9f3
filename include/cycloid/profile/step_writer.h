#ifndef cycloid_profile_step_writer_h
#define cycloid_profile_step_writer_h

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/profile/outline.h>

#include <string>

namespace cycloid
{
  namespace profile
  {
    /**
     * @brief What write_step() put into the file.
     */
    struct StepSummary
    {
      /** Number of points the periodic B-spline interpolates. */
      unsigned int n_spline_points = 0;
      /** Largest distance between the spline and the exact profile at
       * the same parameter [mm] (an upper bound of its distance from the
       * curve), measured at 8 points per spline interval. */
      double max_deviation = 0;
    };

    /**
     * Write the disc of @p outline to @p filename as STEP (AP214, mm)
     * through OpenCASCADE: one planar face in z = 0 whose outer wire is the
     * profile of @p geometry as one periodic cubic B-spline, running
     * counter-clockwise, and whose inner wires are the holes of @p outline
     * as circles, so that CAD can extrude it into the disc.
     *
     * The spline interpolates exact profile points at parameters
     * t = -phi. It is far more accurate than a chord, so it needs far fewer
     * points than the polyline: it starts from 8 points per tooth and
     * halves every spline interval whose deviation from the exact curve
     * exceeds half of the chord tolerance of @p outline, until none does.
     * Throws dealii::ExcMessage if the spline cannot meet the tolerance or
     * the file cannot be written.
     */
    StepSummary
    write_step(const geometry::CycloidGeometry &geometry,
               const DiscOutline               &outline,
               const std::string               &filename);
  } // namespace profile
} // namespace cycloid

#endif

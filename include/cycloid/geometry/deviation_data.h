#ifndef cycloid_geometry_deviation_data_h
#define cycloid_geometry_deviation_data_h

namespace cycloid
{
  namespace geometry
  {
    /**
     * @brief The manufacturing deviations of one pin, as a deviations file
     * gives them (issue #50; the files' format is in doc/user-guide.md).
     */
    struct PinDeviation
    {
      /** Index j of the pin (nominally at rp (cos 2 pi j/zp, sin 2 pi
       * j/zp)). */
      unsigned int pin = 0;
      /** Move of its centre away from the housing centre [um]. */
      double radial_um = 0;
      /** Move of its centre along the counter-clockwise tangent at its
       * nominal position [um]. */
      double tangential_um = 0;
      /** Change of its radius [um]. */
      double radius_um = 0;
      /** Line of the file it was read from (for messages). */
      unsigned int line = 0;
    };

    /**
     * @brief The manufacturing deviations of one disc: of its crank
     * eccentric, the angular placement of its crank holes, and the
     * modifications its profile was ground with.
     */
    struct DiscDeviation
    {
      /** Index of the disc (0 or 1). */
      unsigned int disc = 0;
      /** Error of the eccentricity its centre sits at, along its crank
       * direction [um]; the profile keeps the shape generated with the
       * nominal e. */
      double eccentricity_um = 0;
      /** Turn of the disc about its own centre, counter-clockwise (an index
       * error of its crank holes) [arcmin]. */
      double angle_arcmin = 0;
      /** Added to the profile's Delta rp [um]. */
      double pin_circle_um = 0;
      /** Added to the profile's Delta rrp [um]. */
      double pin_radius_um = 0;
      /** Line of the file it was read from (for messages). */
      unsigned int line = 0;
    };

  } // namespace geometry
} // namespace cycloid

#endif

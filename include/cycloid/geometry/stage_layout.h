#ifndef cycloid_geometry_stage_layout_h
#define cycloid_geometry_stage_layout_h

#include <deal.II/base/point.h>

#include <cycloid/geometry/geometry_parameters.h>

#include <vector>

namespace cycloid
{
  namespace geometry
  {
    /**
     * @brief One pin of the stage as it is: where its centre is and how
     * thick it is.
     */
    struct PinData
    {
      /** Centre in the housing frame [mm]. */
      dealii::Point<2> centre;
      /** Radius [mm]. */
      double radius = 0;
    };

    /**
     * @brief One disc of the stage as it is made and placed: the crank
     * eccentric it rides on, where its crank holes put it about its centre,
     * and the modifications its own profile was ground with.
     */
    struct DiscData
    {
      /** Eccentricity of its crank eccentric [mm]. */
      double eccentricity = 0;
      /** Crank angle of its eccentric ahead of the crank's [rad]: 0 for
       * disc 0, pi for disc 1 (the two discs of an RV stage run half a
       * turn apart). */
      double crank_offset = 0;
      /** Turn of the disc about its centre beyond the kinematic one [rad]
       * (counter-clockwise): an index error of its crank holes. */
      double index_angle = 0;
      /** Pin circle radius modification Delta rp of its profile [mm]. */
      double delta_pin_circle_radius = 0;
      /** Pin radius modification Delta rrp of its profile [mm]. */
      double delta_pin_radius = 0;
      /** Rotation modification delta of its profile [rad]. */
      double rotation_modification = 0;
    };

    /**
     * @brief The stage as data: every pin (centre, radius) and every disc
     * (eccentricity, angular placement, its own profile modifications).
     *
     * Why: the layers that need a pin or a disc (profile, clearances and
     * arms, meshing, contact search, the analytic and reduced models) read
     * it here instead of computing pin j from zp and rp, so a stage whose
     * pins and discs differ from one another (manufacturing deviations)
     * is a different layout, not a different code path. nominal() is the
     * perfectly made stage of the parameter file; its values are computed
     * with the same expressions the geometry used before it had a layout,
     * so nominal results are unchanged to the last bit.
     */
    struct StageLayout
    {
      /** The pins, pin j at index j. */
      std::vector<PinData> pins;
      /** The discs, disc d at index d: always both discs of the stage (a
       * scene with one disc uses disc 0). */
      std::vector<DiscData> discs;

      /** The nominal stage of @p prm: pin j at rp (cos 2 pi j/zp, sin 2 pi
       * j/zp) with radius rrp, rp = e zp / K1; disc 0 and disc 1 on
       * eccentrics e half a turn apart, neither turned, both with the
       * file's modifications. */
      static StageLayout
      nominal(const GeometryParameters &prm);

      /** Number of discs the layout describes. */
      static constexpr unsigned int n_discs = 2;
    };
  } // namespace geometry
} // namespace cycloid

#endif

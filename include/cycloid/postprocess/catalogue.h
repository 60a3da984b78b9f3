#ifndef cycloid_postprocess_catalogue_h
#define cycloid_postprocess_catalogue_h

#include <vector>

namespace cycloid
{
  namespace postprocess
  {
    /**
     * @brief One state of a catalogue torque cycle: the torsion curve's
     * point and the rigid take-up it contains.
     */
    struct TorsionPoint
    {
      /** Crank angle [rad]. */
      double crank = 0;
      /** Output torque [N m]. */
      double torque = 0;
      /** Output rotation beta from the kinematic position [rad]. */
      double rotation = 0;
      /** Rigid take-up rotation in beta (signed like the torque) [rad]. */
      double takeup = 0;
    };

    /**
     * @brief The figures RV reducer catalogues read from the torsion curve
     * of the cycle 0 -> +R -> -R -> 0 (R the rated torque), for the
     * cycloid-pin stage alone (doc/catalogue.md gives the definitions and
     * their source):
     * - torsional rigidity b/a: the torque span b over the twist a it adds
     *   between 50 % and 100 % of R, both directions together;
     * - lost motion: the twist between the mid-points of the hysteresis
     *   width at +3 % and -3 % of R;
     * - backlash: the width of the curve at zero torque.
     * The frictionless model has no hysteresis: its loading and unloading
     * branches coincide, so each mid-point is the common value.
     */
    struct CatalogueFigures
    {
      /** Crank angle of the cycle [rad]. */
      double crank = 0;
      /** Rated torque R [N m]. */
      double rated_torque = 0;
      /** Torsional rigidity b/a [N m/arcmin]. */
      double rigidity_Nm_per_arcmin = 0;
      /** Lost motion [arcmin]. */
      double lost_motion_arcmin = 0;
      /** Backlash [arcmin]. */
      double backlash_arcmin = 0;
      /** The part of the lost motion that is the rigid take-up of the
       * profile clearances [arcmin] (0 without profile modification). */
      double lost_motion_clearance_arcmin = 0;
      /** The elastic rest: contact and body compliance between -3 % and
       * +3 % of R [arcmin]. */
      double lost_motion_elastic_arcmin = 0;
    };

    /**
     * @brief The catalogue figures of the cycle @p curve (the states of one
     * crank angle, in cycle order) with rated torque @p rated [N m], the
     * lost motion read at +-@p lost_motion_fraction of it. The curve must
     * hold states at +-R, +-R/2, +-lost_motion_fraction R and zero torque
     * (the backlash is the spread of the rotations there), as
     * parameters::LoadingParameters::cycle_torques() makes them; a missing
     * one is an error that names it.
     */
    CatalogueFigures
    catalogue_figures(const std::vector<TorsionPoint> &curve,
                      const double                     rated,
                      const double                     lost_motion_fraction);
  } // namespace postprocess
} // namespace cycloid

#endif

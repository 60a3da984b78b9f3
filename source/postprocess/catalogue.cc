#include <deal.II/base/exceptions.h>

#include <cycloid/postprocess/catalogue.h>
#include <cycloid/results/stage_state.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace cycloid
{
  namespace postprocess
  {
    namespace
    {
      /** The mean rotation (and take-up) of the states of @p curve at the
       * torque @p fraction * @p rated: the mid-point of the hysteresis
       * width there (the branches coincide for a frictionless model, so
       * the mean is their common value). */
      TorsionPoint
      at_torque(const std::vector<TorsionPoint> &curve,
                const double                     rated,
                const double                     fraction)
      {
        TorsionPoint mean;
        unsigned int n = 0;
        for (const TorsionPoint &p : curve)
          if (std::abs(p.torque - fraction * rated) <= 1e-9 * rated)
            {
              mean.rotation += p.rotation;
              mean.takeup += p.takeup;
              ++n;
            }
        AssertThrow(n > 0,
                    dealii::ExcMessage(
                      "the torque cycle has no state at " +
                      std::to_string(fraction * 100.) +
                      " % of the rated torque, which the catalogue figures "
                      "read."));
        mean.torque = fraction * rated;
        mean.rotation /= n;
        mean.takeup /= n;
        return mean;
      }
    } // namespace



    CatalogueFigures
    catalogue_figures(const std::vector<TorsionPoint> &curve,
                      const double                     rated,
                      const double                     lost_motion_fraction)
    {
      namespace u = results::units;
      AssertThrow(!curve.empty() && rated > 0, dealii::ExcInternalError());
      const auto theta = [&](const double f) {
        return at_torque(curve, rated, f);
      };
      CatalogueFigures c;
      c.crank        = curve.front().crank;
      c.rated_torque = rated;
      // b/a with both directions: b = R/2 on each side, a the twist added.
      const double a = (theta(1.).rotation - theta(0.5).rotation) +
                       (theta(-0.5).rotation - theta(-1.).rotation);
      c.rigidity_Nm_per_arcmin = rated / a * u::rad_per_arcmin;
      const TorsionPoint plus  = theta(lost_motion_fraction),
                         minus = theta(-lost_motion_fraction);
      c.lost_motion_arcmin =
        (plus.rotation - minus.rotation) * u::arcmin_per_rad;
      c.lost_motion_clearance_arcmin =
        (plus.takeup - minus.takeup) * u::arcmin_per_rad;
      c.lost_motion_elastic_arcmin =
        c.lost_motion_arcmin - c.lost_motion_clearance_arcmin;
      // Backlash: the width of the curve at zero torque, where the states
      // are the limits of the branches on either side.
      double       lo = 1e300, hi = -1e300;
      unsigned int n = 0;
      for (const TorsionPoint &p : curve)
        if (p.torque == 0)
          {
            lo = std::min(lo, p.rotation);
            hi = std::max(hi, p.rotation);
            ++n;
          }
      AssertThrow(n >= 2,
                  dealii::ExcMessage(
                    "the torque cycle has fewer than two zero-torque states "
                    "(one per side), which the backlash reads."));
      c.backlash_arcmin = (hi - lo) * u::arcmin_per_rad;
      return c;
    }
  } // namespace postprocess
} // namespace cycloid

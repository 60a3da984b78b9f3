// StageLayout::nominal(): the perfectly made stage of the parameter file.

#include <deal.II/base/numbers.h>

#include <cycloid/geometry/stage_layout.h>

#include <cmath>

namespace cycloid
{
  namespace geometry
  {
    StageLayout
    StageLayout::nominal(const GeometryParameters &prm)
    {
      constexpr double pi = dealii::numbers::PI;
      // The expressions CycloidGeometry used before the layout existed,
      // term by term, so that nominal results keep every bit.
      const unsigned int zp = prm.n_pins;
      const double       rp =
        prm.shortening_coefficient > 0 ?
                prm.eccentricity * prm.n_pins / prm.shortening_coefficient :
                0.;
      StageLayout layout;
      layout.pins.resize(zp);
      for (unsigned int j = 0; j < zp; ++j)
        {
          const double angle = 2. * pi * j / zp;
          layout.pins[j].centre =
            dealii::Point<2>(rp * std::cos(angle), rp * std::sin(angle));
          layout.pins[j].radius = prm.pin_radius;
        }
      layout.discs.resize(n_discs);
      for (unsigned int d = 0; d < n_discs; ++d)
        {
          DiscData &disc               = layout.discs[d];
          disc.eccentricity            = prm.eccentricity;
          disc.crank_offset            = d == 0 ? 0. : pi;
          disc.index_angle             = 0;
          disc.delta_pin_circle_radius = prm.delta_pin_circle_radius;
          disc.delta_pin_radius        = prm.delta_pin_radius;
          disc.rotation_modification   = prm.rotation_modification_rad;
        }
      return layout;
    }
  } // namespace geometry
} // namespace cycloid

#include <deal.II/base/numbers.h>

#include <cycloid/support/needle_bearing.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace cycloid
{
  namespace support
  {
    namespace
    {
      /** Palmgren's constant [mm N^-0.9 mm^0.8] and exponents. */
      constexpr double palmgren   = 3.84e-5;
      constexpr double load_exp   = 0.9;
      constexpr double length_exp = 0.8;
      constexpr double contacts   = 2.;
    } // namespace



    NeedleBearing::NeedleBearing(const NeedleBearingSize &size)
      : dims(size)
    {}



    double
    NeedleBearing::roller_approach(const double q, const double length)
    {
      return contacts * palmgren * std::pow(std::max(q, 0.), load_exp) /
             std::pow(length, length_exp);
    }



    double
    NeedleBearing::roller_load(const double s, const double length)
    {
      if (s <= 0)
        return 0.;
      return std::pow(s * std::pow(length, length_exp) / (contacts * palmgren),
                      1. / load_exp);
    }



    double
    NeedleBearing::roller_stiffness_at(const double q) const
    {
      // Q = a s^(1/0.9): dQ/ds = Q / (0.9 s), with s = s(Q).
      if (q <= 0)
        return 0.;
      return q / (load_exp * roller_approach(q, dims.roller_length));
    }



    double
    NeedleBearing::energy(const dealii::Tensor<1, 2> &d,
                          const double                cage) const
    {
      // Q = a s^p: its integral is Q s / (p + 1).
      double e = 0;
      for (unsigned int k = 0; k < dims.n_rollers; ++k)
        {
          const double phi =
            cage + 2. * dealii::numbers::PI * k / dims.n_rollers;
          const double s =
            -(d[0] * std::cos(phi) + d[1] * std::sin(phi)) - dims.clearance;
          e += roller_load(s, dims.roller_length) * std::max(s, 0.) /
               (1. / load_exp + 1.);
        }
      return e;
    }



    NeedleBearing::Response
    NeedleBearing::response(const dealii::Tensor<1, 2> &d,
                            const double                cage,
                            const double                floor) const
    {
      Response                          r;
      std::vector<double>               stiffness(dims.n_rollers);
      std::vector<dealii::Tensor<1, 2>> direction(dims.n_rollers);
      for (unsigned int k = 0; k < dims.n_rollers; ++k)
        {
          const double phi =
            cage + 2. * dealii::numbers::PI * k / dims.n_rollers;
          const dealii::Tensor<1, 2> u({std::cos(phi), std::sin(phi)});
          const double               s = -(d * u) - dims.clearance;
          const double               q = roller_load(s, dims.roller_length);
          r.force += q * u;
          if (q > 0)
            {
              ++r.rollers_loaded;
              r.max_roller_load = std::max(r.max_roller_load, q);
            }
          stiffness[k] = roller_stiffness_at(q);
          direction[k] = u;
        }
      // The guard only where no roller carries: a loaded bearing has its
      // own stiffness, and a guard there would slow a disc that floats
      // (its loads vanishing) to a linear convergence.
      for (unsigned int k = 0; k < dims.n_rollers; ++k)
        r.stiffness -= (r.rollers_loaded > 0 ? stiffness[k] : floor) *
                       dealii::outer_product(direction[k], direction[k]);
      return r;
    }
  } // namespace support
} // namespace cycloid

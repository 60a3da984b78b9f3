#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>

#include <cycloid/reduced/local_contact.h>

#include <cmath>

namespace cycloid
{
  namespace reduced
  {
    namespace
    {
      constexpr double pi = dealii::numbers::PI;
    }



    LocalContact::LocalContact(const double load_half_width,
                               const double compliance,
                               const double inverse_radius)
      : w(load_half_width)
      , compliance(compliance)
      , inverse_radius(inverse_radius)
    {
      AssertThrow(w > 0 && compliance > 0 && inverse_radius > 0,
                  dealii::ExcMessage(
                    "reduced model: a contact needs a load half-width, an "
                    "elastic body and a convex pair (1/r > 1/rho)."));
    }



    double
    LocalContact::half_width(const double q) const
    {
      // a = sqrt(4 q R* / (pi E*)), 1/E* = compliance.
      return q > 0 ? std::sqrt(4. * q * compliance / (pi * inverse_radius)) :
                     0.;
    }



    double
    LocalContact::approach(const double q) const
    {
      if (q <= 0)
        return 0.;
      return 2. * q * compliance / pi * (std::log(w / half_width(q)) + 0.25);
    }



    double
    LocalContact::slope(const double q) const
    {
      // d/dq [q (ln w - ln a(q))] with a ~ sqrt(q): ln(w/a) - 1/2.
      return 2. * compliance / pi * (std::log(w / half_width(q)) - 0.25);
    }



    double
    halfspace_axis_approach(const double q,
                            const double a,
                            const double z,
                            const double E,
                            const double nu)
    {
      const double p0a = 2. * q / pi;
      return p0a / E *
             ((1. - nu * nu) * std::asinh(z / a) -
              nu * (1. + nu) * (z * std::sqrt(a * a + z * z) - z * z) /
                (a * a));
    }
    double
    near_field_error(const results::StageState &state, const double pin_radius)
    {
      double a = 0;
      for (const auto &p : state.pins)
        if (p.fn > 0)
          a = std::max(a, p.hertz_halfwidth);
      return near_field_error_factor * (a / pin_radius) * (a / pin_radius);
    }



  } // namespace reduced
} // namespace cycloid

#ifndef cycloid_support_needle_bearing_h
#define cycloid_support_needle_bearing_h

#include <deal.II/base/tensor.h>

#include <cycloid/support/crank_bearing_parameters.h>

namespace cycloid
{
  namespace support
  {
    /**
     * @brief The radial load-deflection law of one needle roller bearing:
     * Z rollers at angles phi_k = cage + 2 pi k / Z, each a
     * compressive-only spring following Palmgren's roller-raceway law
     * delta = 3.84e-5 Q^0.9 / l^0.8 [mm, N, mm] per contact, two contacts
     * per roller (Harris & Kotzalas, Rolling Bearing Analysis). When the
     * crank hole has moved by d against its eccentric, roller k is
     * compressed by s_k = -d . u_k - c (u_k = (cos phi_k, sin phi_k), c the
     * radial clearance) and pushes the bore outwards with Q(s_k) u_k: the
     * load is shared out by the geometry, not by an assumed distribution.
     */
    class NeedleBearing
    {
    public:
      /** The bearing of @p size. */
      explicit NeedleBearing(const NeedleBearingSize &size);

      /** What the bearing does at one deflection. */
      struct Response
      {
        /** Force of the bearing on the disc [N]. */
        dealii::Tensor<1, 2> force;
        /** d force / d deflection [N/mm] (negative semi-definite). */
        dealii::Tensor<2, 2> stiffness;
        /** Rollers carrying load [-]. */
        unsigned int rollers_loaded = 0;
        /** Largest roller load [N]. */
        double max_roller_load = 0;
      };

      /**
       * The response to deflection @p d [mm] (the crank hole's centre
       * against its eccentric's) with the cage at @p cage [rad]. Where no
       * roller carries, each has stiffness @p floor [N/mm] in `stiffness`
       * (a Newton iteration's guard against a bearing that holds nothing;
       * the force is exact).
       */
      Response
      response(const dealii::Tensor<1, 2> &d,
               const double                cage,
               const double                floor = 0) const;

      /** The rollers' elastic energy at deflection @p d [mm] with the cage
       * at @p cage [rad] [N mm]: its derivative is minus the force. */
      double
      energy(const dealii::Tensor<1, 2> &d, const double cage) const;

      /** Approach of one roller's two raceways at load @p q [N] on
       * length @p length [mm] (Palmgren) [mm]. */
      static double
      roller_approach(const double q, const double length);

      /** Load [N] of a roller of length @p length [mm] compressed by
       * @p s [mm] (0 for s <= 0). */
      static double
      roller_load(const double s, const double length);

      /** The roller stiffness dQ/ds [N/mm] at load @p q [N]. */
      double
      roller_stiffness_at(const double q) const;

      /** Stribeck's radial load share of a line-contact bearing with no
       * clearance: Q_max = stribeck_number * F / Z. */
      static constexpr double stribeck_number = 4.08;

      /** The sizes. */
      const NeedleBearingSize &
      size() const
      {
        return dims;
      }

    private:
      const NeedleBearingSize dims;
    };
  } // namespace support
} // namespace cycloid

#endif

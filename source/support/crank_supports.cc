#include <deal.II/base/exceptions.h>

#include <cycloid/support/crank_supports.h>

#include <cmath>

namespace cycloid
{
  namespace support
  {
    namespace
    {
      /** e_z x a. */
      dealii::Tensor<1, 2>
      turn(const dealii::Tensor<1, 2> &a)
      {
        return dealii::Tensor<1, 2>({-a[1], a[0]});
      }
    } // namespace



    CrankSupports::CrankSupports(const CrankBearingParameters    &prm,
                                 const geometry::CycloidGeometry &geo,
                                 const unsigned int               n_discs,
                                 const double                     psi)
      : law(prm.size(geo.parameters().crank_hole_radius,
                     geo.parameters().tooth_width))
    {
      const unsigned int n_cranks = geo.parameters().n_crank_holes;
      AssertThrow(n_cranks >= 2,
                  dealii::ExcMessage(
                    "Crank bearings/Model = needle needs Geometry/Number of "
                    "crank holes >= 2: a disc on one bearing is free to turn "
                    "about it."));
      for (unsigned int d = 0; d < n_discs; ++d)
        {
          const dealii::Point<2>            c = geo.disc_centre(d, psi);
          std::vector<dealii::Tensor<1, 2>> a;
          for (unsigned int j = 0; j < n_cranks; ++j)
            a.push_back(geo.crank_hole_centre(d, j, psi) - c);
          arms.push_back(a);
          cage.push_back(geo.disc_crank_angle(d, psi));
        }
    }



    dealii::Tensor<1, 2>
    CrankSupports::deflection(const unsigned int d,
                              const unsigned int j,
                              const DiscMotion  &motion,
                              const double       beta) const
    {
      return motion.translation + (motion.rotation - beta) * turn(arms[d][j]);
    }



    CrankSupports::Resultant
    CrankSupports::resultant(const unsigned int d,
                             const DiscMotion  &motion,
                             const double       beta,
                             const double       floor) const
    {
      Resultant r;
      for (unsigned int j = 0; j < arms[d].size(); ++j)
        {
          const dealii::Tensor<1, 2> w = turn(arms[d][j]);
          const auto                 b =
            law.response(deflection(d, j, motion, beta), cage[d], floor);
          // The roller forces pass through the hole's centre: moment
          // a x F = w . F.
          r.value[0] += b.force[0];
          r.value[1] += b.force[1];
          r.value[2] += w * b.force;
          // d(deflection)/d(tx, ty, theta, beta) = [I, w, -w].
          const dealii::Tensor<1, 2> kw = b.stiffness * w;
          for (unsigned int a = 0; a < 2; ++a)
            {
              r.derivative(a, 0) += b.stiffness[a][0];
              r.derivative(a, 1) += b.stiffness[a][1];
              r.derivative(a, 2) += kw[a];
              r.derivative(a, 3) -= kw[a];
            }
          const dealii::Tensor<1, 2> wk = w * b.stiffness;
          r.derivative(2, 0) += wk[0];
          r.derivative(2, 1) += wk[1];
          r.derivative(2, 2) += w * kw;
          r.derivative(2, 3) -= w * kw;
        }
      return r;
    }



    std::vector<results::BearingState>
    CrankSupports::states(const unsigned int d,
                          const DiscMotion  &motion,
                          const double       beta) const
    {
      std::vector<results::BearingState> out;
      for (unsigned int j = 0; j < arms[d].size(); ++j)
        {
          const dealii::Tensor<1, 2> delta = deflection(d, j, motion, beta);
          const auto                 b     = law.response(delta, cage[d]);
          results::BearingState      s;
          s.disc            = d;
          s.crank           = j;
          s.fx              = b.force[0];
          s.fy              = b.force[1];
          s.deflection      = delta.norm();
          s.rollers_loaded  = b.rollers_loaded;
          s.max_roller_load = b.max_roller_load;
          out.push_back(s);
        }
      return out;
    }



    double
    CrankSupports::work(const unsigned int d,
                        const DiscMotion  &motion,
                        const double       beta) const
    {
      double w = 0;
      for (unsigned int j = 0; j < arms[d].size(); ++j)
        {
          const dealii::Tensor<1, 2> delta = deflection(d, j, motion, beta);
          w -= law.response(delta, cage[d]).force * delta;
        }
      return w;
    }



    double
    CrankSupports::energy(const unsigned int d,
                          const DiscMotion  &motion,
                          const double       beta) const
    {
      double e = 0;
      for (unsigned int j = 0; j < arms[d].size(); ++j)
        e += law.energy(deflection(d, j, motion, beta), cage[d]);
      return e;
    }



    double
    CrankSupports::stiffness_floor(const double torque) const
    {
      // A roller's share of the torque's crank forces, over how far a
      // roller moves before and while it carries it: the secant stiffness
      // at that load, across the clearance.
      const double arm = arms[0][0].norm();
      const double per_roller =
        std::max(std::abs(torque), 1e-12) /
        (arm * arms.size() * arms[0].size() * law.size().n_rollers);
      return 1e-2 * per_roller /
             (law.size().clearance +
              NeedleBearing::roller_approach(per_roller,
                                             law.size().roller_length));
    }
  } // namespace support
} // namespace cycloid

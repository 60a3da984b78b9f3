// DiscProfile: the exact curve of one disc's (modified) profile, its
// closest points and the closed forms of the textbook profile.

#include <deal.II/base/numbers.h>

#include <cycloid/geometry/disc_profile.h>
#include <cycloid/geometry/safeguarded_newton.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

namespace cycloid
{
  namespace geometry
  {
    namespace
    {
      using complex = std::complex<double>;

      constexpr double pi = dealii::numbers::PI;

      inline Tensor<1, 2>
      to_tensor(const complex &z)
      {
        Tensor<1, 2> t;
        t[0] = z.real();
        t[1] = z.imag();
        return t;
      }

      inline double
      cross(const Tensor<1, 2> &a, const Tensor<1, 2> &b)
      {
        return a[0] * b[1] - a[1] * b[0];
      }
    } // namespace



    DiscProfile::DiscProfile(const GeometryParameters &prm,
                             const double              rp,
                             const DiscData           &disc)
      : zp(prm.n_pins)
      , zc(prm.n_teeth)
      , e(prm.eccentricity)
      , i_h(static_cast<double>(prm.n_pins) / std::max(1u, prm.n_teeth))
      , big_r(rp + disc.delta_pin_circle_radius)
      , small_r(prm.pin_radius + disc.delta_pin_radius)
      , k_mod(big_r > 0 ? prm.eccentricity * prm.n_pins / big_r : 0.)
      , delta(disc.rotation_modification)
      , delta_rp(disc.delta_pin_circle_radius)
      , delta_rrp(disc.delta_pin_radius)
    {}



    double
    DiscProfile::root_radius() const
    {
      return big_r - e - small_r;
    }



    double
    DiscProfile::tip_radius() const
    {
      return big_r + e - small_r;
    }



    double
    DiscProfile::s_function(const double phi) const
    {
      return 1. + k_mod * k_mod - 2. * k_mod * std::cos(phi);
    }



    void
    DiscProfile::evaluate(const double  phi,
                          Tensor<1, 2> &p,
                          Tensor<1, 2> &dp,
                          Tensor<1, 2> &ddp,
                          Tensor<1, 2> &normal) const
    {
      const complex I(0., 1.);
      const double  inv_zc = 1. / zc;
      const complex ea     = std::polar(1., -phi * inv_zc);
      const complex eg     = std::polar(1., -i_h * phi);

      // Pin-centre curve C and its unnormalised outward normal u.
      const complex c   = big_r * ea - e * eg;
      const complex u   = ea - k_mod * eg;
      const complex du  = -I * inv_zc * ea + I * i_h * k_mod * eg;
      const complex ddu = -inv_zc * inv_zc * ea + i_h * i_h * k_mod * eg;
      const complex dc  = -I * (big_r * inv_zc) * u;
      const complex ddc = -I * (big_r * inv_zc) * du;

      const double S    = s_function(phi);
      const double sphi = std::sin(phi), cphi = std::cos(phi);
      const double s  = 1. / std::sqrt(S);
      const double s3 = s * s * s;
      const double ds = -k_mod * sphi * s3;
      const double dds =
        -k_mod * cphi * s3 + 3. * k_mod * k_mod * sphi * sphi * s3 * s * s;

      const complex P   = c - small_r * u * s;
      const complex dP  = dc - small_r * (du * s + u * ds);
      const complex ddP = ddc - small_r * (ddu * s + 2. * du * ds + u * dds);

      const complex turn = std::polar(1., -delta);
      p                  = to_tensor(turn * P);
      dp                 = to_tensor(turn * dP);
      ddp                = to_tensor(turn * ddP);
      normal             = to_tensor(turn * u * s);
    }



    ProfilePoint
    DiscProfile::profile(const double phi) const
    {
      Tensor<1, 2> p, dp, ddp, n;
      evaluate(phi, p, dp, ddp, n);
      ProfilePoint result;
      result.phi        = phi;
      result.point      = Point<2>(p);
      result.derivative = dp;
      result.normal     = n;

      // Signed curvature kappa = (P' x P'') / |P'|^3 of the curve as
      // traversed; its centre lies at P + (1/kappa) * left normal. Convert
      // to "positive where the centre of curvature is outside the disc".
      const double speed = dp.norm();
      const double kappa = cross(dp, ddp) / (speed * speed * speed);
      Tensor<1, 2> left;
      left[0]           = -dp[1] / speed;
      left[1]           = dp[0] / speed;
      const double side = (left * n) >= 0 ? 1. : -1.;
      result.curvature_radius =
        (kappa != 0.) ? side / kappa : std::numeric_limits<double>::infinity();
      return result;
    }



    Tensor<1, 2>
    DiscProfile::profile_second_derivative(const double phi) const
    {
      Tensor<1, 2> p, dp, ddp, n;
      evaluate(phi, p, dp, ddp, n);
      return ddp;
    }



    ProfilePoint
    DiscProfile::closest_point(const Point<2> &q) const
    {
      // Initial window from the polar angle of q: the profile point of
      // parameter phi lies near polar angle -phi/zc - delta.
      const double theta = std::atan2(q[1], q[0]) + delta;
      const double phi0  = -theta * zc;

      // Cheap evaluation of the point only, for the coarse sampling.
      const complex turn   = std::polar(1., -delta);
      const double  inv_zc = 1. / zc;
      const complex qz(q[0], q[1]);
      const auto    distance2 = [&](const double phi) {
        const complex ea = std::polar(1., -phi * inv_zc);
        const complex eg = std::polar(1., -i_h * phi);
        const double  s  = 1. / std::sqrt(s_function(phi));
        const complex P =
          turn * (big_r * ea - e * eg - small_r * s * (ea - k_mod * eg));
        return std::norm(P - qz);
      };

      // The window of 2.5 teeth is wide enough: the polar angle of P(phi)
      // departs from -phi/zc by less than (e + r)/root radius, i.e. by less
      // than (e + r) zc / root radius ~ 1.6 rad of phi for the seed case.
      const unsigned int n_samples = 32;
      const double       lo        = phi0 - 1.25 * pi;
      const double       h         = 2.5 * pi / n_samples;
      double             best      = std::numeric_limits<double>::max();
      unsigned int       best_k    = 0;
      for (unsigned int k = 0; k <= n_samples; ++k)
        {
          const double d2 = distance2(lo + k * h);
          if (d2 < best)
            {
              best   = d2;
              best_k = k;
            }
        }

      // Safeguarded Newton on g(phi) = (P - q) . P' inside the bracket of
      // the best sample's neighbours.
      const double a        = lo + (best_k == 0 ? 0 : best_k - 1) * h;
      const double b        = lo + std::min(best_k + 1, n_samples) * h;
      const auto   g_and_dg = [&](const double x, double &g, double &dg) {
        Tensor<1, 2> p, dp, ddp, n;
        evaluate(x, p, dp, ddp, n);
        const Tensor<1, 2> d = p - q;
        g                    = d * dp;
        dg                   = dp * dp + d * ddp;
      };
      double ga, gb, dg;
      g_and_dg(a, ga, dg);
      g_and_dg(b, gb, dg);
      return profile(
        safeguarded_newton(
          g_and_dg, lo + best_k * h, a, b, ga <= 0 && gb >= 0, 1e-15, 60)
          .x);
    }



    double
    DiscProfile::signed_distance(const Point<2> &q, ProfilePoint *closest) const
    {
      const ProfilePoint cp = closest_point(q);
      if (closest != nullptr)
        *closest = cp;
      const Tensor<1, 2> d = q - cp.point;
      return (d * cp.normal >= 0 ? 1. : -1.) * d.norm();
    }



    double
    DiscProfile::closed_form_curvature_radius(const double phi) const
    {
      const double S = s_function(phi);
      const double T =
        k_mod * (1. + zp) * std::cos(phi) - (1. + zp * k_mod * k_mod);
      return big_r * S * std::sqrt(S) / T + small_r;
    }



    double
    DiscProfile::first_order_clearance(const double phi) const
    {
      const double S = s_function(phi);
      return delta_rrp - delta_rp * (1. - k_mod * std::cos(phi)) / std::sqrt(S);
    }



    double
    DiscProfile::seed_backlash(const double phi) const
    {
      const double S  = s_function(phi);
      const double sq = std::sqrt(S);
      return delta_rrp * (1. - std::sin(phi) / sq) -
             delta_rp *
               (1. - k_mod * std::cos(phi) -
                std::sqrt(1. - k_mod * k_mod) * std::sin(phi)) /
               sq;
    }



    double
    DiscProfile::closed_form_arm(const double phi) const
    {
      return e * zc * std::sin(phi) / std::sqrt(s_function(phi));
    }



    double
    DiscProfile::undercut_margin() const
    {
      // rho_C = R S^{3/2} / T is the pin-centre curve's curvature radius
      // (negative on the convex part); sample half a tooth (symmetric).
      double             smallest  = std::numeric_limits<double>::max();
      const unsigned int n_samples = 2000;
      for (unsigned int k = 0; k <= n_samples; ++k)
        {
          const double phi = pi * k / n_samples;
          const double S   = s_function(phi);
          const double T =
            k_mod * (1. + zp) * std::cos(phi) - (1. + zp * k_mod * k_mod);
          if (T < 0)
            smallest = std::min(smallest, -big_r * S * std::sqrt(S) / T);
        }
      return smallest - small_r;
    }
  } // namespace geometry
} // namespace cycloid

#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>

#include <cycloid/analytic/analytic_parameters.h>
#include <cycloid/analytic/load_distribution.h>
#include <cycloid/analytic/pair_stiffness.h>
#include <cycloid/geometry/safeguarded_newton.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

namespace cycloid
{
  namespace analytic
  {
    namespace
    {
      constexpr double pi = dealii::numbers::PI;

      /** 1/rho with 1/inf = 0. */
      inline double
      inverse_radius(const double rho)
      {
        return std::isfinite(rho) ? 1. / rho : 0.;
      }
    } // namespace



    double
    hertz_half_width(const double force,
                     const double b,
                     const double r,
                     const double rho,
                     const double e_disc,
                     const double e_pin)
    {
      if (force <= 0)
        return 0.;
      const double inv_r = 1. / r - inverse_radius(rho);
      const double inv_e = 1. / e_disc + (e_pin > 0 ? 1. / e_pin : 0.);
      return std::sqrt(4. * force * inv_e / (dealii::numbers::PI * b * inv_r));
    }



    double
    stage_hertz_half_width(const double                          force,
                           const double                          rho,
                           const double                          pin_radius,
                           const geometry::GeometryParameters   &geometry,
                           const parameters::MaterialParameters &material,
                           const parameters::SceneParameters    &scene)
    {
      const bool rigid =
        scene.pins == parameters::SceneParameters::PinModel::rigid;
      return hertz_half_width(force,
                              geometry.tooth_width,
                              pin_radius,
                              rho,
                              material.disc.plane_strain_modulus(),
                              rigid ? 0. : material.pin.plane_strain_modulus());
    }



    namespace
    {
      /** Tresca stress / p0 on the axis of Hertz's line contact at depth
       * t = z / a (plane strain, Poisson's ratio @p nu). */
      double
      axis_tresca_ratio(const double t, const double nu)
      {
        const double root    = std::sqrt(1. + t * t);
        const double sigma_x = -((1. + 2. * t * t) / root - 2. * t);
        const double sigma_z = -1. / root;
        const double sigma_y = nu * (sigma_x + sigma_z);
        const auto [lo, hi]  = std::minmax({sigma_x, sigma_y, sigma_z});
        return (hi - lo) / 2.;
      }
    } // namespace



    SubsurfaceShear
    hertz_subsurface_shear(const double poisson)
    {
      // A scan brackets the maximum (the Tresca stress may have a kink
      // where the middle principal stress changes), golden sections refine
      // it.
      const unsigned int n     = 400;
      const double       t_max = 4.;
      unsigned int       best  = 0;
      for (unsigned int i = 1; i <= n; ++i)
        if (axis_tresca_ratio(t_max * i / n, poisson) >
            axis_tresca_ratio(t_max * best / n, poisson))
          best = i;
      double       lo = t_max * (best > 0 ? best - 1 : 0) / n;
      double       hi = t_max * std::min(best + 1, n) / n;
      const double g  = (std::sqrt(5.) - 1.) / 2.;
      while (hi - lo > 1e-12)
        {
          const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
          if (axis_tresca_ratio(a, poisson) > axis_tresca_ratio(b, poisson))
            hi = b;
          else
            lo = a;
        }
      const double t = (lo + hi) / 2.;
      return {axis_tresca_ratio(t, poisson), t};
    }



    void
    set_hertz_stresses(results::PinState &pin,
                       const double       tooth_width,
                       const double       poisson)
    {
      const double a = pin.hertz_halfwidth;
      if (pin.fn <= 0 || a <= 0)
        return;
      pin.hertz_pressure =
        2. * pin.fn / (dealii::numbers::PI * a * tooth_width);
      // The ratios depend on nu only: computed once per nu (a few hundred
      // stress evaluations), not for every pin of every state.
      static double          cached_poisson = -2;
      static SubsurfaceShear shear;
      if (poisson != cached_poisson)
        {
          shear          = hertz_subsurface_shear(poisson);
          cached_poisson = poisson;
        }
      pin.max_shear_stress = shear.stress_ratio * pin.hertz_pressure;
      pin.max_shear_depth  = shear.depth_ratio * a;
    }



    void
    AnalyticParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii::Patterns;
      prm.enter_subsection("Analytic");
      {
        prm.declare_entry(
          "Pair stiffness model",
          "line-contact",
          Selection(PairStiffnessModel::model_names()),
          "Stiffness of one pin-disc pair: 'seed' (the seed article's linear "
          "Hertz spring, times the load sharing coefficient) or "
          "'line-contact' (load-dependent approach of two cylinders with the "
          "logarithmic term, Puttock & Thwaite 1969 / Johnson 1985).");
        prm.declare_entry("Load sharing coefficient",
                          "0.7",
                          Double(0, 1),
                          "The seed's coefficient lambda for manufacturing "
                          "errors [-]; multiplies the 'seed' pair stiffness "
                          "only.");
        prm.declare_entry("Tolerance",
                          "1e-12",
                          Double(1e-16, 1e-3),
                          "Relative tolerance of the torque balance of the "
                          "load distribution [-].");
        prm.declare_entry("Maximum iterations",
                          "200",
                          Integer(1, 100000),
                          "Iteration limit of the load-distribution solve "
                          "[-].");
      }
      prm.leave_subsection();
    }



    void
    AnalyticParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Analytic");
      {
        pair_model               = prm.get("Pair stiffness model");
        load_sharing_coefficient = prm.get_double("Load sharing coefficient");
        tolerance                = prm.get_double("Tolerance");
        max_iterations           = prm.get_integer("Maximum iterations");
      }
      prm.leave_subsection();
      AssertThrow(load_sharing_coefficient > 0,
                  dealii::ExcMessage(
                    "Analytic/Load sharing coefficient must be positive."));
    }



    std::string
    PairStiffnessModel::model_names()
    {
      return "seed|line-contact";
    }



    std::unique_ptr<PairStiffnessModel>
    PairStiffnessModel::create(const AnalyticParameters             &parameters,
                               const parameters::MaterialParameters &material,
                               const parameters::SceneParameters    &scene,
                               const double tooth_width)
    {
      const double e_disc = material.disc.plane_strain_modulus();
      const double e_pin =
        scene.pins == parameters::SceneParameters::PinModel::rigid ?
          0. :
          material.pin.plane_strain_modulus();
      if (parameters.pair_model == "seed")
        return std::make_unique<SeedPairStiffness>(
          tooth_width, e_disc, e_pin, parameters.load_sharing_coefficient);
      if (parameters.pair_model == "line-contact")
        return std::make_unique<LineContactPairStiffness>(tooth_width,
                                                          e_disc,
                                                          e_pin);
      AssertThrow(false,
                  dealii::ExcMessage("Analytic/Pair stiffness model: unknown "
                                     "model '" +
                                     parameters.pair_model + "'."));
      return nullptr;
    }



    SeedPairStiffness::SeedPairStiffness(const double tooth_width,
                                         const double disc_modulus,
                                         const double pin_modulus,
                                         const double lambda)
      : b(tooth_width)
      , e_disc(disc_modulus)
      , e_pin(pin_modulus)
      , lambda(lambda)
    {}



    double
    SeedPairStiffness::stiffness(const double, const PairGeometry &pair) const
    {
      const double r       = pair.pin_radius;
      const double inv_rho = inverse_radius(pair.profile_curvature_radius);
      // Combined curvature radius a: 1/a = 1/r - 1/rho (rho > 0 concave).
      const double inv_a = 1. / r - inv_rho;
      AssertThrow(inv_a > 0,
                  dealii::ExcMessage(
                    "seed pair stiffness: conformal contact (profile "
                    "curvature radius not larger than the pin radius)."));
      const double a = 1. / inv_a;
      // Seed: t_z = 4 F a/(pi b E' r_z), t_b = 4 F a/(pi b E' a_b).
      const double c_pin  = (e_pin > 0) ? 4. * a / (pi * b * e_pin * r) : 0.;
      const double c_disc = 4. * a * std::abs(inv_rho) / (pi * b * e_disc);
      return lambda / (c_pin + c_disc);
    }



    double
    SeedPairStiffness::force(const double        approach,
                             const PairGeometry &pair) const
    {
      return approach > 0 ? stiffness(approach, pair) * approach : 0.;
    }



    double
    SeedPairStiffness::approach(const double        force,
                                const PairGeometry &pair) const
    {
      return force > 0 ? force / stiffness(0., pair) : 0.;
    }



    LineContactPairStiffness::LineContactPairStiffness(
      const double tooth_width,
      const double disc_modulus,
      const double pin_modulus)
      : b(tooth_width)
      , c_disc(1. / disc_modulus)
      , c_pin(pin_modulus > 0 ? 1. / pin_modulus : 0.)
    {}



    double
    LineContactPairStiffness::half_width(const double        force,
                                         const PairGeometry &pair) const
    {
      const double inv_r =
        1. / pair.pin_radius - inverse_radius(pair.profile_curvature_radius);
      AssertThrow(inv_r > 0,
                  dealii::ExcMessage(
                    "line-contact pair stiffness: conformal contact (profile "
                    "curvature radius not larger than the pin radius)."));
      // a = sqrt(4 F R* / (pi b E*)), 1/E* = c_pin + c_disc.
      return std::sqrt(4. * force * (c_pin + c_disc) / (pi * b * inv_r));
    }



    double
    LineContactPairStiffness::approach(const double        force,
                                       const PairGeometry &pair) const
    {
      if (force <= 0)
        return 0.;
      const double a = half_width(force, pair);
      return 2. * force / (pi * b) *
             (c_pin * (std::log(4. * pair.pin_radius / a) - 0.5) +
              c_disc * (std::log(4. * pair.disc_depth / a) - 0.5));
    }



    double
    LineContactPairStiffness::compliance(const double        force,
                                         const PairGeometry &pair) const
    {
      const double a = half_width(force, pair);
      return 2. / (pi * b) *
             (c_pin * (std::log(4. * pair.pin_radius / a) - 1.) +
              c_disc * (std::log(4. * pair.disc_depth / a) - 1.));
    }



    double
    LineContactPairStiffness::force(const double        target,
                                    const PairGeometry &pair) const
    {
      if (target <= 0)
        return 0.;
      // delta(F) is increasing (while the half-width is below 4R/e) and
      // concave, and delta(0) = 0 < target: bracket the root in (0, upper]
      // by doubling, then Newton inside the bracket.
      const auto in_range = [&](const double f) {
        AssertThrow(compliance(f, pair) > 0,
                    dealii::ExcMessage(
                      "line-contact pair stiffness: load beyond the model's "
                      "range (contact half-width comparable to the pin "
                      "radius)."));
      };
      const double start = target / compliance(1000., pair);
      double       upper = start;
      for (in_range(upper); approach(upper, pair) < target; in_range(upper))
        upper *= 2;
      const auto residual = [&](const double f, double &value, double &slope) {
        value = approach(f, pair) - target;
        slope = compliance(f, pair);
      };
      const geometry::NewtonResult root = geometry::safeguarded_newton(
        residual, std::min(start, upper), 0., upper, true, 1e-15, 200);
      AssertThrow(root.converged,
                  dealii::ExcMessage("line-contact pair stiffness: the "
                                     "force-approach inversion did not "
                                     "converge."));
      return root.x;
    }



    double
    LineContactPairStiffness::stiffness(const double        approach,
                                        const PairGeometry &pair) const
    {
      if (approach <= 0)
        return 0.;
      return 1. / compliance(force(approach, pair), pair);
    }



    double
    LoadState::k_secant() const
    {
      return rotation != 0 ? torque / rotation :
                             std::numeric_limits<double>::quiet_NaN();
    }



    double
    LoadState::k_secant_elastic() const
    {
      return rotation != takeup ? torque / (rotation - takeup) :
                                  std::numeric_limits<double>::quiet_NaN();
    }



    LoadDistribution::LoadDistribution(const PairStiffnessModel &model,
                                       const double       relative_tolerance,
                                       const unsigned int max_iterations)
      : model(model)
      , tolerance(relative_tolerance)
      , max_iterations(max_iterations)
    {}



    double
    LoadDistribution::torque_at(const double          beta,
                                std::vector<PinLoad> &pins,
                                double               &slope) const
    {
      double torque = 0;
      slope         = 0;
      for (PinLoad &p : pins)
        {
          const double l = p.contact.arm;
          // Clearances within round-off below zero count as touching.
          const double c = std::max(p.contact.clearance, 0.);
          p.approach     = std::max(beta * l - c, 0.);
          p.force        = model.force(p.approach, p.pair);
          p.stiffness =
            p.approach > 0 ? model.stiffness(p.approach, p.pair) : 0.;
          torque += p.force * l;
          slope += p.stiffness * l * l;
        }
      return torque;
    }



    namespace
    {
      /** Take-up: the smallest rotation that closes a clearance on the
       * loaded side (arm of the sign @p sign) [rad, unsigned]. */
      double
      takeup_rotation(const std::vector<PinLoad> &pins, const double sign)
      {
        double takeup = std::numeric_limits<double>::max();
        for (const PinLoad &p : pins)
          if (sign * p.contact.arm > 1e-9)
            takeup = std::min(takeup,
                              std::max(p.contact.clearance, 0.) /
                                (sign * p.contact.arm));
        AssertThrow(takeup < std::numeric_limits<double>::max(),
                    dealii::ExcMessage("load distribution: no pin can carry "
                                       "a torque of this sign."));
        return takeup;
      }
    } // namespace



    LoadState
    LoadDistribution::zero_torque_limit(const std::vector<PinLoad> &pins,
                                        const int                   side) const
    {
      LoadState state;
      state.pins     = pins;
      state.torque   = 0;
      state.takeup   = side * takeup_rotation(pins, side);
      state.rotation = state.takeup;
      double slope   = 0;
      state.reaction_torque =
        torque_at(state.rotation, state.pins, slope) * 1e-3;
      // The one-sided slope at first contact is not a stiffness of the
      // stage (the other side is the clearance), as in the FE limit.
      state.k_tangent = std::numeric_limits<double>::quiet_NaN();
      return state;
    }



    double
    LoadDistribution::carrying_rotation(
      const std::function<double(double, double &)> &torque_of,
      const double                                   goal,
      const double                                   sign,
      const double                                   takeup,
      const double                                   beta_guess,
      double                                        &dg,
      unsigned int                                  &iterations) const
    {
      // Bracket [lo, hi] in terms of x = sign * beta (x >= takeup).
      const auto g = [&](const double x, double &slope) {
        return sign * torque_of(sign * x, slope);
      };
      double lo   = takeup;
      double step = 1e-6;
      if (sign * beta_guess > takeup)
        step = sign * beta_guess - takeup;
      double       hi       = lo + step;
      unsigned int n_expand = 0;
      while (g(hi, dg) < goal)
        {
          lo = hi;
          step *= 2.;
          hi = lo + step;
          AssertThrow(++n_expand < 200,
                      dealii::ExcMessage("load distribution: cannot bracket "
                                         "the rotation that carries the "
                                         "torque."));
        }

      double       x  = (sign * beta_guess > lo && sign * beta_guess < hi) ?
                          sign * beta_guess :
                          hi;
      unsigned int it = 0;
      for (; it < max_iterations; ++it)
        {
          const double r = g(x, dg) - goal;
          if (std::abs(r) <= tolerance * goal)
            break;
          if (r < 0)
            lo = x;
          else
            hi = x;
          double next = (dg > 0) ? x - r / dg : 0.5 * (lo + hi);
          if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
          // Stop where the rotation cannot resolve the torque any more: at
          // a tiny torque after a take-up, beta = takeup + a tiny excess, and
          // the approach beta arm - clearance cancels all but a few digits.
          if (hi - lo <= 1e-16 * std::abs(hi) ||
              std::abs(next - x) <= 4e-16 * std::abs(x))
            break;
          x = next;
        }
      if (it == max_iterations)
        {
          std::ostringstream msg;
          msg << "load distribution did not converge in " << max_iterations
              << " iterations (Analytic/Maximum iterations) for torque "
              << sign * goal * 1e-3 << " N m.";
          AssertThrow(false, dealii::ExcMessage(msg.str()));
        }
      iterations = it + n_expand;
      return x;
    }



    LoadState
    LoadDistribution::solve(const std::vector<PinLoad> &pins_in,
                            const double                torque,
                            const double                beta_guess) const
    {
      LoadState state;
      state.torque        = torque;
      state.pins          = pins_in;
      const double target = torque * 1e3; // N m -> N mm
      const double sign   = torque >= 0 ? 1. : -1.;
      double       slope  = 0;

      const double takeup = takeup_rotation(state.pins, sign);
      state.takeup        = sign * takeup;

      if (torque == 0)
        {
          state.rotation        = 0;
          state.reaction_torque = torque_at(0., state.pins, slope) * 1e-3;
          state.k_tangent       = slope * 1e-3;
          return state;
        }
      const auto torque_of = [&](const double beta, double &dg) {
        return torque_at(beta, state.pins, dg);
      };
      double       dg       = 0;
      const double x        = carrying_rotation(torque_of,
                                         std::abs(target),
                                         sign,
                                         takeup,
                                         beta_guess,
                                         dg,
                                         state.iterations);
      const double t        = torque_of(sign * x, dg);
      state.rotation        = sign * x;
      state.reaction_torque = t * 1e-3;
      state.k_tangent       = dg * 1e-3;
      for (const PinLoad &p : state.pins)
        if (p.force > 0)
          ++state.pins_in_contact;
      state.breakdown.bodies   = 0;
      state.breakdown.bearings = 0;
      state.breakdown.contacts = state.rotation;
      return state;
    }
  } // namespace analytic
} // namespace cycloid

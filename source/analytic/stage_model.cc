#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>

#include <cycloid/analytic/stage_model.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace cycloid
{
  namespace analytic
  {
    StageModel::StageModel(const ModelSettings &parameters)
      : prm(parameters)
      , geo(parameters.geometry)
      , model(PairStiffnessModel::create(parameters.analytic,
                                         parameters.material,
                                         parameters.scene,
                                         parameters.geometry.tooth_width))
      , distribution(*model,
                     parameters.analytic.tolerance,
                     parameters.analytic.max_iterations)
    {}



    double
    StageModel::disc_depth(const dealii::Point<2> &p) const
    {
      const auto &g = prm.geometry;
      if (prm.scene.load_introduction ==
            parameters::SceneParameters::LoadIntroduction::crank_holes &&
          g.n_crank_holes > 0)
        {
          double depth = std::numeric_limits<double>::max();
          for (unsigned int k = 0; k < g.n_crank_holes; ++k)
            {
              depth = std::min(depth,
                               p.distance(geo.crank_hole_centre(k)) -
                                 g.crank_hole_radius);
            }
          return depth;
        }
      return p.norm() - g.bore_radius;
    }



    std::vector<PinLoad>
    StageModel::unloaded_pins(const double psi) const
    {
      std::vector<PinLoad> pins;
      for (unsigned int d = 0; d < prm.scene.n_discs; ++d)
        for (const geometry::PinContact &c : geo.pin_contacts(d, psi))
          {
            if (c.clearance < -1e-7)
              {
                std::ostringstream msg;
                msg << "pin " << c.pin << " overlaps disc " << d << " by "
                    << -c.clearance * 1e3 << " um at crank angle "
                    << psi * 180. / dealii::numbers::PI
                    << " deg: the scene cannot start from a negative "
                       "clearance.";
                AssertThrow(false, dealii::ExcMessage(msg.str()));
              }
            PinLoad p;
            p.contact                       = c;
            p.pair.phase                    = c.phase;
            p.pair.profile_curvature_radius = c.curvature_radius;
            p.pair.pin_radius               = geo.pin_radius(c.pin);
            p.pair.disc_depth =
              disc_depth(geo.to_disc(d, psi, c.contact_point));
            pins.push_back(p);
          }
      return pins;
    }



    results::StageState
    StageModel::stage_state(const LoadState &load, const double psi) const
    {
      results::StageState s;
      s.crank           = psi;
      s.torque          = load.torque;
      s.rotation        = load.rotation;
      s.k_tangent       = load.k_tangent;
      s.takeup          = load.takeup;
      s.reaction_torque = load.reaction_torque;
      s.iterations      = load.iterations;
      s.bearings        = load.bearings;
      s.breakdown       = load.breakdown;
      s.pins.reserve(load.pins.size());
      for (const PinLoad &p : load.pins)
        {
          results::PinState r;
          r.disc              = p.contact.disc;
          r.pin               = p.contact.pin;
          r.fx                = -p.force * p.contact.normal[0];
          r.fy                = -p.force * p.contact.normal[1];
          r.fn                = p.force;
          r.arm               = p.contact.arm;
          r.clearance         = p.contact.clearance;
          r.phase             = p.contact.phase;
          r.approach          = p.approach;
          r.pair_stiffness    = p.stiffness;
          r.contact_point     = p.contact.contact_point;
          r.hertz_halfwidth   = stage_hertz_half_width(p.force,
                                                     p.contact.curvature_radius,
                                                     p.pair.pin_radius,
                                                     prm.geometry,
                                                     prm.material,
                                                     prm.scene);
          r.contact_halfwidth = r.hertz_halfwidth;
          set_hertz_stresses(r,
                             prm.geometry.tooth_width,
                             prm.material.disc.poissons_ratio);
          r.max_pressure = r.hertz_pressure;
          s.pins.push_back(r);
        }
      return s;
    }



    LoadState
    StageModel::solve(const double psi,
                      const double torque,
                      const double beta_guess) const
    {
      return solve(unloaded_pins(psi), torque, beta_guess, psi);
    }
  } // namespace analytic
} // namespace cycloid

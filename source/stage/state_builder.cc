#include <deal.II/base/exceptions.h>

#include <cycloid/analytic/pair_stiffness.h>
#include <cycloid/stage/state_builder.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace cycloid
{
  namespace stage
  {
    namespace u = results::units;



    template <int dim>
    StateBuilder<dim>::StateBuilder(const StateBuilderSettings      &settings,
                                    const geometry::CycloidGeometry &geo,
                                    const contact::ContactProblem<dim> &contact)
      : settings(settings)
      , geo(geo)
      , contact(contact)
    {}



    template <int dim>
    results::StageState
    StateBuilder<dim>::empty_state() const
    {
      const unsigned int  zp = settings.geometry.n_pins;
      results::StageState s;
      s.crank = settings.psi;
      s.dofs  = contact.elasticity().n_dofs();
      s.pins.resize(settings.scene.n_discs * zp);
      for (unsigned int k = 0; k < s.pins.size(); ++k)
        {
          s.pins[k].disc = k / zp;
          s.pins[k].pin  = k % zp;
        }
      return s;
    }



    template <int dim>
    results::StageState
    StateBuilder<dim>::state(const contact::ContactState &result,
                             const double                 torque) const
    {
      results::StageState s = empty_state();
      s.torque              = torque;
      s.rotation            = result.beta;
      s.k_tangent  = result.tangent * settings.width_scale * u::Nm_per_Nmm;
      s.iterations = result.iterations;
      s.linear_iterations     = result.linear_iterations;
      s.preconditioner_setups = result.preconditioner_setups;
      s.cycles_broken         = result.cycles_broken;
      s.cycle_tension         = result.cycle_tension;
      sum_pin_forces(s.pins);
      set_pin_geometry(s);
      set_peak_pressures(s.pins);
      const int sign = s.torque >= 0 ? 1 : -1;
      s.takeup       = sign * takeup_rotation(sign);
      return s;
    }



    template <int dim>
    results::StageState
    StateBuilder<dim>::zero_torque_limit(const int side) const
    {
      // T -> 0 on one side: the discs turned by the take-up towards that
      // side, every pin just touching or clear, no force, no solve.
      results::StageState s = empty_state();
      s.torque              = 0;
      s.takeup              = side * takeup_rotation(side);
      s.rotation            = s.takeup;
      s.k_tangent           = std::numeric_limits<double>::quiet_NaN();
      set_pin_geometry(s);
      return s;
    }



    template <int dim>
    double
    StateBuilder<dim>::takeup_rotation(const int sign) const
    {
      // Rigid take-up (lost motion) of the exact geometry, as in the
      // analytical model: the rotation that closes the first clearance of
      // any disc on the side of the torque's sign.
      double takeup = std::numeric_limits<double>::max();
      for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
        for (const auto &pc : geo.pin_contacts(d, settings.psi))
          if (sign * pc.arm > 1e-9)
            takeup =
              std::min(takeup, std::max(pc.clearance, 0.) / std::abs(pc.arm));
      AssertThrow(takeup < std::numeric_limits<double>::max(),
                  dealii::ExcMessage("no pin can carry a torque of this sign "
                                     "at this crank angle."));
      return takeup;
    }



    template <int dim>
    void
    StateBuilder<dim>::sum_pin_forces(
      std::vector<results::PinState> &pins) const
    {
      const unsigned int  zp        = settings.geometry.n_pins;
      const double        scale     = settings.width_scale;
      const auto         &slaves    = contact.slave_nodes();
      const auto         &reactions = contact.slave_reactions();
      std::vector<double> moment(pins.size(), 0.);
      for (const unsigned int i : contact.active_set())
        {
          const auto            &s = slaves[i];
          const unsigned int     k = s.body * zp + s.cylinder;
          const dealii::Point<2> c = geo.disc_centre(s.body, settings.psi);
          // Reactions are in the mesh axes; the disc has turned by delta
          // since the mesh's crank angle (transient runs): housing frame.
          const double delta = geo.disc_rotation(s.body, settings.psi) -
                               geo.disc_rotation(s.body, settings.psi_mesh);
          const double rx = reactions[i][0] * scale,
                       ry = reactions[i][1] * scale;
          const double gx = std::cos(delta) * rx - std::sin(delta) * ry,
                       gy = std::sin(delta) * rx + std::cos(delta) * ry;
          pins[k].fx += gx;
          pins[k].fy += gy;
          ++pins[k].active_nodes;
          moment[k] +=
            (s.position[0] - c[0]) * gy - (s.position[1] - c[1]) * gx;
        }
      for (unsigned int k = 0; k < pins.size(); ++k)
        {
          auto &p = pins[k];
          p.fn    = std::hypot(p.fx, p.fy);
          // The pin's force on the disc resists a positive torque:
          // arm = -(r x F)/|F|.
          if (p.fn > 0)
            p.arm = -moment[k] / p.fn;
        }
    }



    template <int dim>
    void
    StateBuilder<dim>::set_pin_geometry(results::StageState &s) const
    {
      const unsigned int zp = settings.geometry.n_pins;
      for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
        for (const auto &pc : geo.pin_contacts(d, settings.psi))
          {
            auto &p = s.pins[d * zp + pc.pin];
            if (p.fn == 0)
              p.arm = pc.arm;
            p.clearance     = pc.clearance;
            p.phase         = pc.phase;
            p.contact_point = pc.contact_point;
            p.approach      = s.rotation * pc.arm - pc.clearance;
            p.hertz_halfwidth =
              analytic::stage_hertz_half_width(p.fn,
                                               pc.curvature_radius,
                                               geo.pin_radius(pc.pin),
                                               settings.geometry,
                                               settings.material,
                                               settings.scene);
            if (p.fn > 0)
              {
                p.contact_halfwidth =
                  contact_halfwidth(d, pc.pin, pc.contact_point);
                const double h =
                  flank_node_spacing(d, pc.pin, pc.contact_point);
                if (h > 0)
                  p.hertz_nodes = 2. * p.hertz_halfwidth / h;
              }
            analytic::set_hertz_stresses(p,
                                         settings.geometry.tooth_width,
                                         settings.material.disc.poissons_ratio);
            s.reaction_torque += p.fn * p.arm * u::Nm_per_Nmm;
          }
    }



    template <int dim>
    void
    StateBuilder<dim>::set_peak_pressures(
      std::vector<results::PinState> &pins) const
    {
      // Nodal pressure = normal reaction / the node's share of the slave
      // surface (as in the VTU field); the model's reactions are already
      // per unit thickness in 2D, so no width scaling.
      const unsigned int zp        = settings.geometry.n_pins;
      const auto        &slaves    = contact.slave_nodes();
      const auto        &reactions = contact.slave_reactions();
      for (const unsigned int i : contact.active_set())
        {
          const auto &s = slaves[i];
          if (s.weight <= 0)
            continue;
          auto &p = pins[s.body * zp + s.cylinder];
          p.max_pressure =
            std::max(p.max_pressure, (reactions[i] * s.normal) / s.weight);
        }
    }



    template <int dim>
    std::vector<std::pair<double, bool>>
    StateBuilder<dim>::pair_node_angles(
      const unsigned int      d,
      const unsigned int      j,
      const dealii::Point<2> &contact_point) const
    {
      const auto            &slaves = contact.slave_nodes();
      const auto            &active = contact.active_set();
      const dealii::Point<2> c      = geo.pin_centre(j);
      const double           a0     = angle_about(contact_point, c, 0.);
      std::vector<std::pair<double, bool>> angles;
      for (unsigned int i = 0; i < slaves.size(); ++i)
        if (slaves[i].body == d && slaves[i].cylinder == j)
          angles.emplace_back(angle_about(slaves[i].position, c, a0),
                              active.count(i) > 0);
      return angles;
    }



    template <int dim>
    double
    StateBuilder<dim>::contact_halfwidth(
      const unsigned int      d,
      const unsigned int      j,
      const dealii::Point<2> &contact_point) const
    {
      // Half the arc between the outermost active nodes of this pair, plus
      // half a node spacing on each side.
      const auto angles = pair_node_angles(d, j, contact_point);
      double     lo = 1e300, hi = -1e300, spacing = 1e300;
      for (const auto &[a, is_active] : angles)
        if (is_active)
          {
            lo = std::min(lo, a);
            hi = std::max(hi, a);
          }
      if (hi < lo)
        return 0.;
      for (const auto &[a, is_active] : angles)
        if (a > hi + 1e-12 || a < lo - 1e-12)
          spacing =
            std::min(spacing, std::min(std::abs(a - hi), std::abs(a - lo)));
      if (spacing > 1e200)
        spacing = 0;
      return geo.pin_radius(j) * (0.5 * (hi - lo) + 0.5 * spacing);
    }



    template <int dim>
    double
    StateBuilder<dim>::flank_node_spacing(
      const unsigned int      d,
      const unsigned int      j,
      const dealii::Point<2> &contact_point) const
    {
      // The distinct angles (3D: the axial nodes of a flank line share
      // one), sorted; the contact point lies at angle 0.
      std::vector<double> a;
      for (const auto &[angle, is_active] :
           pair_node_angles(d, j, contact_point))
        a.push_back(angle);
      std::sort(a.begin(), a.end());
      a.erase(std::unique(a.begin(),
                          a.end(),
                          [](const double x, const double y) {
                            return std::abs(x - y) < 1e-9;
                          }),
              a.end());
      if (a.size() < 2)
        return 0.;
      const auto nearest = std::min_element(a.begin(),
                                            a.end(),
                                            [](const double x, const double y) {
                                              return std::abs(x) < std::abs(y);
                                            });
      double     gap     = 1e300;
      if (nearest != a.begin())
        gap = std::min(gap, *nearest - *std::prev(nearest));
      if (std::next(nearest) != a.end())
        gap = std::min(gap, *std::next(nearest) - *nearest);
      return geo.pin_radius(j) * gap;
    }



    template class StateBuilder<2>;
    template class StateBuilder<3>;
  } // namespace stage
} // namespace cycloid

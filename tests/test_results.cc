// The flat buffer of a state (results::StateBuffer), in which the phase
// groups of a sweep send their states to world rank 0: every field of a
// state and of each pin comes back exactly, and a buffer of the wrong size
// is refused.

#include <deal.II/base/exceptions.h>

#include <cycloid/results/error_estimate.h>
#include <cycloid/results/state_buffer.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace cycloid;

namespace
{
  /** A state whose every field holds a value of its own (none zero, the
   * integers above 2^32 where the type allows), with @p n_pins pins. */
  results::StageState
  distinct_state(const unsigned int n_pins)
  {
    results::StageState s;
    s.step                  = 7;
    s.crank                 = 0.123456789012345;
    s.torque                = -987.654321;
    s.rotation              = 1.5e-4;
    s.k_tangent             = 6.02e6;
    s.takeup                = -3.25e-5;
    s.reaction_torque       = 987.6543;
    s.iterations            = 11;
    s.preconditioner_setups = 13;
    s.linear_iterations     = 5000000000ul;
    s.cycles_broken         = 3;
    s.cycle_tension         = 4.5e-7;
    s.dofs                  = 6000000001ul;
    s.wall_s                = 2.718281828459045;
    s.peak_memory_MB        = 1234.5;
    s.error.k_secant        = 0.0123;
    s.error.k_tangent       = 0.0456;
    s.error.max_pin_force   = 0.0789;
    s.error.bulk            = 0.0012;
    s.error.model           = 0.0034;
    s.error.contact_level   = 3;
    s.error.failure         = "x";
    s.breakdown.contacts    = 1.25e-5;
    s.breakdown.bodies      = 2.5e-5;
    s.breakdown.bearings    = 1e-4;
    for (unsigned int j = 0; j < n_pins % 7; ++j)
      {
        results::BearingState b;
        b.disc            = j % 2;
        b.crank           = j / 2;
        b.fx              = 1234.5 + j;
        b.fy              = -987.25 * j;
        b.deflection      = 3.5e-3 * (j + 1);
        b.rollers_loaded  = 5 + j;
        b.max_roller_load = 456.75 * (j + 1);
        s.bearings.push_back(b);
      }
    for (unsigned int j = 0; j < n_pins; ++j)
      {
        results::PinState p;
        const double      x = 1. + j / 7.;
        p.disc              = j % 2;
        p.pin               = j;
        p.fx                = 1.1 * x;
        p.fy                = -2.2 * x;
        p.fn                = 3.3 * x;
        p.arm               = 4.4 * x;
        p.clearance         = 5.5e-3 * x;
        p.phase             = 0.66 * x;
        p.approach          = -7.7e-3 * x;
        p.pair_stiffness    = 8.8e5 * x;
        p.contact_point     = dealii::Point<2>(9.9 * x, -10.1 * x);
        p.contact_halfwidth = 0.11 * x;
        p.hertz_halfwidth   = 0.12 * x;
        p.max_pressure      = 1300. * x;
        p.hertz_pressure    = 1400. * x;
        p.max_shear_stress  = 450. * x;
        p.max_shear_depth   = 0.16 * x;
        p.active_nodes      = 17 + j;
        p.fn_error          = 0.17 * x;
        p.hertz_nodes       = 0.18 * x;
        s.pins.push_back(p);
      }
    return s;
  }
} // namespace



TEST(StateBuffer, StructsHaveTheFieldsThePackingKnows)
{
  // A field added to PinState or StageState changes these sizes: add it to
  // for_each_field()/for_each_pin_field() (source/results/state_buffer.cc)
  // and to distinct_state() above, then update the sizes.
  EXPECT_EQ(sizeof(results::PinState),
            2 * sizeof(unsigned int) + 16 * sizeof(double) +
              2 * sizeof(unsigned int) /* active_nodes + padding */ +
              2 * sizeof(double) /* fn_error, hertz_nodes */);
  EXPECT_EQ(sizeof(results::ErrorEstimate),
            5 * sizeof(double) +
              2 * sizeof(unsigned int) /* contact_level + padding */ +
              2 * sizeof(std::string) /* failure, method (not packed) */);
  EXPECT_EQ(sizeof(results::StageState),
            2 * sizeof(unsigned int) /* step + padding */ + 6 * sizeof(double) +
              sizeof(std::vector<results::PinState>) +
              sizeof(results::ErrorEstimate) + 2 * sizeof(unsigned int) +
              sizeof(unsigned long) +
              2 * sizeof(unsigned int) /* cycles_broken + padding */ +
              sizeof(double) /* cycle_tension */ + sizeof(unsigned long) +
              2 * sizeof(double) + sizeof(std::vector<results::BearingState>) +
              sizeof(results::ComplianceBreakdown));
  EXPECT_EQ(sizeof(results::BearingState),
            2 * sizeof(unsigned int) + 3 * sizeof(double) +
              2 * sizeof(unsigned int) /* rollers_loaded + padding */ +
              sizeof(double));
  EXPECT_EQ(sizeof(results::ComplianceBreakdown), 3 * sizeof(double));
}



TEST(StateBuffer, EveryFieldComesBackExactly)
{
  for (const unsigned int n_pins : {0u, 1u, 80u})
    {
      const results::StageState a      = distinct_state(n_pins);
      const std::vector<double> buffer = results::StateBuffer::pack(a);
      EXPECT_EQ(buffer.size(), 27u + 21u * n_pins + 7u * (n_pins % 7));
      const results::StageState b = results::StateBuffer::unpack(buffer);
      EXPECT_EQ(b.step, a.step);
      EXPECT_EQ(b.crank, a.crank);
      EXPECT_EQ(b.torque, a.torque);
      EXPECT_EQ(b.rotation, a.rotation);
      EXPECT_EQ(b.k_tangent, a.k_tangent);
      EXPECT_EQ(b.takeup, a.takeup);
      EXPECT_EQ(b.reaction_torque, a.reaction_torque);
      EXPECT_EQ(b.iterations, a.iterations);
      EXPECT_EQ(b.preconditioner_setups, a.preconditioner_setups);
      EXPECT_EQ(b.linear_iterations, a.linear_iterations);
      EXPECT_EQ(b.cycles_broken, a.cycles_broken);
      EXPECT_EQ(b.cycle_tension, a.cycle_tension);
      EXPECT_EQ(b.dofs, a.dofs);
      EXPECT_EQ(b.wall_s, a.wall_s);
      EXPECT_EQ(b.peak_memory_MB, a.peak_memory_MB);
      EXPECT_EQ(b.error.k_secant, a.error.k_secant);
      EXPECT_EQ(b.error.k_tangent, a.error.k_tangent);
      EXPECT_EQ(b.error.max_pin_force, a.error.max_pin_force);
      EXPECT_EQ(b.error.bulk, a.error.bulk);
      EXPECT_EQ(b.error.model, a.error.model);
      EXPECT_EQ(b.error.contact_level, a.error.contact_level);
      EXPECT_FALSE(b.error.failure.empty());
      EXPECT_EQ(b.breakdown.contacts, a.breakdown.contacts);
      EXPECT_EQ(b.breakdown.bodies, a.breakdown.bodies);
      EXPECT_EQ(b.breakdown.bearings, a.breakdown.bearings);
      ASSERT_EQ(b.bearings.size(), a.bearings.size());
      for (unsigned int j = 0; j < a.bearings.size(); ++j)
        {
          const results::BearingState &p = a.bearings[j], &q = b.bearings[j];
          EXPECT_EQ(q.disc, p.disc);
          EXPECT_EQ(q.crank, p.crank);
          EXPECT_EQ(q.fx, p.fx);
          EXPECT_EQ(q.fy, p.fy);
          EXPECT_EQ(q.deflection, p.deflection);
          EXPECT_EQ(q.rollers_loaded, p.rollers_loaded);
          EXPECT_EQ(q.max_roller_load, p.max_roller_load);
        }
      ASSERT_EQ(b.pins.size(), a.pins.size());
      for (unsigned int j = 0; j < n_pins; ++j)
        {
          const results::PinState &p = a.pins[j], &q = b.pins[j];
          EXPECT_EQ(q.disc, p.disc);
          EXPECT_EQ(q.pin, p.pin);
          EXPECT_EQ(q.fx, p.fx);
          EXPECT_EQ(q.fy, p.fy);
          EXPECT_EQ(q.fn, p.fn);
          EXPECT_EQ(q.arm, p.arm);
          EXPECT_EQ(q.clearance, p.clearance);
          EXPECT_EQ(q.phase, p.phase);
          EXPECT_EQ(q.approach, p.approach);
          EXPECT_EQ(q.pair_stiffness, p.pair_stiffness);
          EXPECT_EQ(q.contact_point, p.contact_point);
          EXPECT_EQ(q.contact_halfwidth, p.contact_halfwidth);
          EXPECT_EQ(q.hertz_halfwidth, p.hertz_halfwidth);
          EXPECT_EQ(q.max_pressure, p.max_pressure);
          EXPECT_EQ(q.hertz_pressure, p.hertz_pressure);
          EXPECT_EQ(q.max_shear_stress, p.max_shear_stress);
          EXPECT_EQ(q.max_shear_depth, p.max_shear_depth);
          EXPECT_EQ(q.active_nodes, p.active_nodes);
          EXPECT_EQ(q.fn_error, p.fn_error);
          EXPECT_EQ(q.hertz_nodes, p.hertz_nodes);
        }
      // The derived figures follow.
      EXPECT_EQ(b.pins_in_contact(), a.pins_in_contact());
      EXPECT_EQ(b.max_pin_force(), a.max_pin_force());
    }
}



TEST(StateBuffer, BufferOfTheWrongSizeIsRefused)
{
  std::vector<double> buffer = results::StateBuffer::pack(distinct_state(3));
  buffer.pop_back();
  EXPECT_THROW(results::StateBuffer::unpack(buffer), dealii::ExceptionBase);
  EXPECT_THROW(results::StateBuffer::unpack(buffer.data(), 5),
               dealii::ExceptionBase);
}



TEST(ResolutionIndicator, ReadsTheMostLoadedPin)
{
  // C / n of the most loaded pin, whatever the other pins' resolution: a
  // lightly loaded pin's narrow Hertz zone is resolved by fewer nodes,
  // but its error relative to the largest force is smaller
  // (doc/error-estimate.md, "The resolution indicator").
  results::StageState s;
  s.pins.resize(3);
  s.pins[0].fn          = 100.;
  s.pins[0].hertz_nodes = 0.5;
  s.pins[1].fn          = 900.;
  s.pins[1].hertz_nodes = 3.;
  s.pins[2].fn          = 0.;
  EXPECT_DOUBLE_EQ(results::resolution_error(s),
                   results::resolution_constant / 9.);
  // Halving the spacing doubles n and quarters the indicator (second
  // order).
  s.pins[1].hertz_nodes = 6.;
  EXPECT_DOUBLE_EQ(results::resolution_error(s),
                   results::resolution_constant / 36.);
  // No contact mesh (analytic, reduced) or no force: no indicator.
  s.pins[1].hertz_nodes = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(results::resolution_error(s)));
  results::StageState unloaded;
  unloaded.pins.resize(2);
  EXPECT_TRUE(std::isnan(results::resolution_error(unloaded)));
}

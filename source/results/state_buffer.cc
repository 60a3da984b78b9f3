#include <deal.II/base/exceptions.h>

#include <cycloid/results/state_buffer.h>

#include <string>
#include <type_traits>

namespace cycloid
{
  namespace results
  {
    namespace
    {
      // The one list of fields of each struct: pack() and unpack() both
      // call these, with a const or a mutable struct, so the two cannot
      // disagree on the order.
      template <typename State, typename Field>
      void
      for_each_field(State &s, Field &&f)
      {
        f(s.step);
        f(s.crank);
        f(s.torque);
        f(s.rotation);
        f(s.k_tangent);
        f(s.takeup);
        f(s.reaction_torque);
        f(s.iterations);
        f(s.preconditioner_setups);
        f(s.linear_iterations);
        f(s.cycles_broken);
        f(s.cycle_tension);
        f(s.dofs);
        f(s.wall_s);
        f(s.peak_memory_MB);
        f(s.error.k_secant);
        f(s.error.k_tangent);
        f(s.error.max_pin_force);
        f(s.error.bulk);
        f(s.error.model);
        f(s.error.contact_level);
        f(s.breakdown.contacts);
        f(s.breakdown.bodies);
        f(s.breakdown.bearings);
      }

      template <typename Bearing, typename Field>
      void
      for_each_bearing_field(Bearing &b, Field &&f)
      {
        f(b.disc);
        f(b.crank);
        f(b.fx);
        f(b.fy);
        f(b.deflection);
        f(b.rollers_loaded);
        f(b.max_roller_load);
      }

      template <typename Pin, typename Field>
      void
      for_each_pin_field(Pin &p, Field &&f)
      {
        f(p.disc);
        f(p.pin);
        f(p.fx);
        f(p.fy);
        f(p.fn);
        f(p.arm);
        f(p.clearance);
        f(p.phase);
        f(p.approach);
        f(p.pair_stiffness);
        f(p.contact_point[0]);
        f(p.contact_point[1]);
        f(p.contact_halfwidth);
        f(p.hertz_halfwidth);
        f(p.max_pressure);
        f(p.hertz_pressure);
        f(p.max_shear_stress);
        f(p.max_shear_depth);
        f(p.active_nodes);
        f(p.fn_error);
        f(p.hertz_nodes);
      }

      /** Number of doubles of the fields of a state and of a pin. */
      template <typename T, typename Visit>
      unsigned int
      count(Visit &&visit)
      {
        T            x{};
        unsigned int n = 0;
        visit(x, [&n](auto &) { ++n; });
        return n;
      }

      unsigned int
      n_state_fields()
      {
        return count<StageState>(
          [](StageState &s, auto &&f) { for_each_field(s, f); });
      }

      unsigned int
      n_pin_fields()
      {
        return count<PinState>(
          [](PinState &p, auto &&f) { for_each_pin_field(p, f); });
      }

      unsigned int
      n_bearing_fields()
      {
        return count<BearingState>(
          [](BearingState &b, auto &&f) { for_each_bearing_field(b, f); });
      }
    } // namespace



    std::vector<double>
    StateBuffer::pack(const StageState &state)
    {
      std::vector<double> buffer;
      buffer.reserve(n_state_fields() + 3 + state.pins.size() * n_pin_fields() +
                     state.bearings.size() * n_bearing_fields());
      const auto put = [&buffer](const auto &x) {
        buffer.push_back(static_cast<double>(x));
      };
      for_each_field(state, put);
      // The reason of a failed estimate travels as a flag only, and the
      // estimate's `method` not at all: it names the reduced model's
      // companion, and only FE phase groups send states.
      buffer.push_back(state.error.failure.empty() ? 0. : 1.);
      buffer.push_back(state.pins.size());
      for (const PinState &p : state.pins)
        for_each_pin_field(p, put);
      buffer.push_back(state.bearings.size());
      for (const BearingState &b : state.bearings)
        for_each_bearing_field(b, put);
      return buffer;
    }



    StageState
    StateBuffer::unpack(const double *data, const unsigned int size)
    {
      const unsigned int header = n_state_fields() + 2;
      AssertThrow(size >= header,
                  dealii::ExcMessage("StateBuffer: " + std::to_string(size) +
                                     " doubles are too few for a state."));
      const unsigned int n_pins = static_cast<unsigned int>(data[header - 1]);
      const unsigned int at_bearings = header + n_pins * n_pin_fields();
      AssertThrow(size > at_bearings,
                  dealii::ExcMessage("StateBuffer: " + std::to_string(size) +
                                     " doubles do not hold a state with " +
                                     std::to_string(n_pins) + " pins."));
      const unsigned int n_bearings =
        static_cast<unsigned int>(data[at_bearings]);
      AssertThrow(size == at_bearings + 1 + n_bearings * n_bearing_fields(),
                  dealii::ExcMessage("StateBuffer: " + std::to_string(size) +
                                     " doubles do not hold a state with " +
                                     std::to_string(n_pins) + " pins and " +
                                     std::to_string(n_bearings) +
                                     " bearings."));
      unsigned int i   = 0;
      const auto   get = [data, &i](auto &x) {
        x = static_cast<std::remove_reference_t<decltype(x)>>(data[i++]);
      };
      StageState state;
      for_each_field(state, get);
      if (data[i++] != 0.)
        state.error.failure = "the coarser contact level failed; the phase "
                              "group's own console says why";
      ++i; // the number of pins
      state.pins.resize(n_pins);
      for (PinState &p : state.pins)
        for_each_pin_field(p, get);
      ++i; // the number of bearings
      state.bearings.resize(n_bearings);
      for (BearingState &b : state.bearings)
        for_each_bearing_field(b, get);
      return state;
    }
  } // namespace results
} // namespace cycloid

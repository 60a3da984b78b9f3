#include <deal.II/base/exceptions.h>

#include <cycloid/results/error_estimate.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace cycloid
{
  namespace results
  {
    void
    set_error_estimate(const StageState  &coarser,
                       const StageState  &coarse,
                       StageState        &fine,
                       const unsigned int level)
    {
      AssertThrow(coarser.pins.size() == fine.pins.size() &&
                    coarse.pins.size() == fine.pins.size(),
                  dealii::ExcDimensionMismatch(coarse.pins.size(),
                                               fine.pins.size()));
      const double w = previous_change_weight;
      // max(|last change|, w |change before|) relative to |reference|.
      const auto estimate = [w](const double q2,
                                const double q1,
                                const double q0,
                                const double reference) {
        if (!std::isfinite(q0) || !std::isfinite(q1) || !std::isfinite(q2) ||
            reference == 0)
          return std::numeric_limits<double>::quiet_NaN();
        return std::max(std::abs(q0 - q1), w * std::abs(q1 - q2)) /
               std::abs(reference);
      };
      auto &e         = fine.error;
      e.k_secant      = estimate(coarser.k_secant(),
                            coarse.k_secant(),
                            fine.k_secant(),
                            fine.k_secant());
      e.k_tangent     = estimate(coarser.k_tangent,
                             coarse.k_tangent,
                             fine.k_tangent,
                             fine.k_tangent);
      e.contact_level = level;
      double largest  = 0;
      for (unsigned int k = 0; k < fine.pins.size(); ++k)
        {
          auto &p = fine.pins[k];
          p.fn_error =
            estimate(coarser.pins[k].fn, coarse.pins[k].fn, p.fn, 1.);
          largest = std::max(largest, p.fn_error);
        }
      const double f_max = fine.max_pin_force();
      e.max_pin_force =
        f_max > 0 ? largest / f_max : std::numeric_limits<double>::quiet_NaN();
    }



    void
    set_error_estimate(const StageState  &coarse,
                       StageState        &fine,
                       const std::string &method)
    {
      AssertThrow(coarse.pins.size() == fine.pins.size(),
                  dealii::ExcDimensionMismatch(coarse.pins.size(),
                                               fine.pins.size()));
      const auto change = [](const double q0, const double q1, const double r) {
        return std::isfinite(q0) && std::isfinite(q1) && r != 0 ?
                 std::abs(q0 - q1) / std::abs(r) :
                 std::numeric_limits<double>::quiet_NaN();
      };
      auto &e     = fine.error;
      e.k_secant  = change(fine.k_secant(), coarse.k_secant(), fine.k_secant());
      e.k_tangent = change(fine.k_tangent, coarse.k_tangent, fine.k_tangent);
      e.method    = method;
      double largest = 0;
      for (unsigned int k = 0; k < fine.pins.size(); ++k)
        {
          auto &p    = fine.pins[k];
          p.fn_error = change(p.fn, coarse.pins[k].fn, 1.);
          largest    = std::max(largest, p.fn_error);
        }
      const double f_max = fine.max_pin_force();
      e.max_pin_force =
        f_max > 0 ? largest / f_max : std::numeric_limits<double>::quiet_NaN();
    }



    void
    add_model_error(const double part, StageState &state)
    {
      auto &e = state.error;
      AssertThrow(e.available(),
                  dealii::ExcMessage("a model error is added to an estimate"));
      e.k_secant += part;
      e.k_tangent += part;
      e.max_pin_force += part;
      const double f_max = state.max_pin_force();
      for (auto &p : state.pins)
        p.fn_error += part * f_max;
      e.model = part;
    }



    BulkError
    bulk_error(const StageState &bulk, const StageState &state)
    {
      AssertThrow(bulk.pins.size() == state.pins.size(),
                  dealii::ExcDimensionMismatch(bulk.pins.size(),
                                               state.pins.size()));
      const double f = bulk_change_factor;
      BulkError    b;
      b.k_secant  = f * std::abs(bulk.k_secant() / state.k_secant() - 1);
      b.k_tangent = f * std::abs(bulk.k_tangent / state.k_tangent - 1);
      for (unsigned int k = 0; k < state.pins.size(); ++k)
        b.fn.push_back(f * std::abs(bulk.pins[k].fn - state.pins[k].fn));
      return b;
    }



    void
    add_bulk_error(const BulkError &b, StageState &state)
    {
      AssertThrow(b.fn.size() == state.pins.size(),
                  dealii::ExcDimensionMismatch(b.fn.size(), state.pins.size()));
      auto &e = state.error;
      e.k_secant += b.k_secant;
      e.k_tangent += b.k_tangent;
      double largest = 0, pins = 0;
      for (unsigned int k = 0; k < state.pins.size(); ++k)
        {
          auto &p = state.pins[k];
          p.fn_error += b.fn[k];
          largest = std::max(largest, p.fn_error);
          pins    = std::max(pins, b.fn[k]);
        }
      const double f_max = state.max_pin_force();
      e.max_pin_force =
        f_max > 0 ? largest / f_max : std::numeric_limits<double>::quiet_NaN();
      e.bulk =
        std::max({b.k_secant, b.k_tangent, f_max > 0 ? pins / f_max : 0.});
    }



    double
    resolution_error(const StageState &state)
    {
      const auto most = state.most_loaded_pin();
      if (most == state.pins.end() || !(most->fn > 0) ||
          !(most->hertz_nodes > 0))
        return std::numeric_limits<double>::quiet_NaN();
      return resolution_constant / (most->hertz_nodes * most->hertz_nodes);
    }



    std::vector<std::string>
    unresolved_pins(const StageState &state, const double threshold)
    {
      std::vector<std::string> pins;
      const double             f_max = state.max_pin_force();
      if (!(f_max > 0))
        return pins;
      for (const auto &p : state.pins)
        if (p.fn_error > threshold * f_max)
          {
            std::ostringstream item;
            item.precision(2);
            item << "disc " << p.disc << " pin " << p.pin << " ("
                 << 100. * p.fn_error / f_max << " %)";
            pins.push_back(item.str());
          }
      return pins;
    }
  } // namespace results
} // namespace cycloid

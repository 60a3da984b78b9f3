#ifndef cycloid_dynamics_time_control_h
#define cycloid_dynamics_time_control_h

#include <deal.II/base/exceptions.h>

#include <cycloid/dynamics/transient_parameters.h>
#include <cycloid/results/stage_state.h>

#include <algorithm>
#include <cmath>

namespace cycloid
{
  namespace dynamics
  {
    /**
     * @brief Time stepping of a transient run (Lethe's SimulationControl in
     * small): the step, the number of steps, where the run stops, the crank
     * angle and the load at a time, and which steps write output,
     * checkpoints and progress lines. Knows nothing of the time scheme.
     */
    class TimeControl
    {
    public:
      /** Time control of @p t, starting at crank angle @p crank0 [rad],
       * ramping to the load @p load (torque [N m] or rotation [rad]). */
      TimeControl(const TransientParameters &t,
                  const double               crank0,
                  const double               load)
        : t(t)
        , crank0(crank0)
        , value(load)
        , steps(
            static_cast<unsigned int>(std::llround(t.end_time / t.time_step)))
      {
        AssertThrow(t.end_time >= t.time_step,
                    dealii::ExcMessage(
                      "Transient/End time must be at least one Time step."));
      }

      /** Time step [s]. */
      double
      time_step() const
      {
        return t.time_step;
      }

      /** Steps to the end time. */
      unsigned int
      n_steps() const
      {
        return steps;
      }

      /** The last step of this run (`Stop after step`, or the end). */
      unsigned int
      last_step() const
      {
        return t.stop_after_step > 0 ? std::min(t.stop_after_step, steps) :
                                       steps;
      }

      /** Time at the end of step @p step [s]. */
      double
      time(const unsigned int step) const
      {
        return step * t.time_step;
      }

      /** Does the crank turn (the discs must be placed every step)? */
      bool
      crank_turns() const
      {
        return t.crank_speed != 0.;
      }

      /** Crank angle at time @p time [rad]. */
      double
      crank_angle(const double time) const
      {
        return crank0 + t.crank_speed * results::units::rad_per_deg * time;
      }

      /** Crank angle swept by the whole run [rad] (the mesh is refined
       * along it). */
      double
      crank_sweep() const
      {
        return t.crank_speed * results::units::rad_per_deg * t.end_time;
      }

      /** Load at time @p time: a smooth (1 - cos) ramp over `Ramp time`,
       * then constant. */
      double
      load(const double time) const
      {
        const double tr = t.ramp_time;
        if (tr <= 0 || time >= tr)
          return value;
        return value * 0.5 * (1. - std::cos(results::units::pi * time / tr));
      }

      /** Does step @p step write the solution fields? */
      bool
      output_due(const unsigned int step) const
      {
        return t.output_interval > 0 && step % t.output_interval == 0;
      }

      /** Does step @p step write a checkpoint? */
      bool
      checkpoint_due(const unsigned int step) const
      {
        return t.checkpoint_interval > 0 && step % t.checkpoint_interval == 0;
      }

      /** Does step @p step print a progress line (run started after
       * @p first)? */
      bool
      progress_due(const unsigned int step, const unsigned int first) const
      {
        return step == first + 1 || step % 10 == 0 || step == last_step();
      }

    private:
      const TransientParameters t;
      const double              crank0;
      const double              value;
      const unsigned int        steps;
    };
  } // namespace dynamics
} // namespace cycloid

#endif

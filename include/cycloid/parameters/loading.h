#ifndef cycloid_parameters_loading_h
#define cycloid_parameters_loading_h

#include <deal.II/base/numbers.h>
#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <vector>

namespace cycloid
{
  namespace parameters
  {
    /**
     * @brief Load states to solve (subsection `Loading`): one or several
     * output torques at one crank angle, or at `Number of phases` crank
     * angles spread over one mesh period 360/zp degrees (both ends
     * included, so the first and last phase are one period apart).
     */
    struct LoadingParameters
    {
      /** Output torques of the whole stage [N m], solved in this order. */
      std::vector<double> torques{1000.};
      /** FE runs: prescribe rotations instead of torques. */
      bool rotation_control = false;
      /** Rotations for rotation control [degrees]. */
      std::vector<double> rotations_deg{0.01};
      /** Rated torque of the catalogue torque cycle [N m]. */
      double rated_torque = 1000.;
      /** Solve the catalogue torque cycle 0 -> +rated -> -rated -> 0
       * instead of the Torque list. */
      bool torque_cycle = false;
      /** Steps of the torque cycle (a multiple of 4: a quarter per
       * branch). */
      unsigned int torque_cycle_steps = 40;
      /** Relative torque at which catalogues read the lost motion
       * (+-3 % of the rated torque). */
      static constexpr double lost_motion_torque = 0.03;

      /**
       * The torques [N m] of the catalogue cycle in cycle order: four
       * branches 0 -> +R -> 0 -> -R -> 0 in torque_cycle_steps / 4 equal
       * steps each, plus the states the catalogue figures read (+-3 % and
       * +-50 % of R) where the steps miss them. The zero between the
       * branches appears twice, as the end of one branch and the start of
       * the next: a frictionless stage at zero torque may rest anywhere in
       * its clearance, so the runs report each zero as the limit of its
       * branch (zero_side()), and the torsion curve is vertical there.
       */
      std::vector<double>
      cycle_torques() const;

      /** Whether @p torque is a state of the torque cycle that the
       * catalogue figures are read at, +-rated torque, which the console
       * always shows (a long cycle shows about every other state). */
      bool
      is_rated_state(const double torque) const
      {
        return torque_cycle && std::abs(torque) == rated_torque;
      }

      /** The side (+1 or -1) from which the zero torque @p loads[i] of a
       * torque cycle is approached: that of the branch it ends (the
       * torque before it), or for the first zero of a branch, of the branch
       * it starts. */
      static int
      zero_side(const std::vector<double> &loads, const unsigned int i);

      /** The side(s) the torques @p loads load: +1 (all positive or
       * zero), -1 (all negative or zero) or 0 (both signs: every pin may
       * touch either flank). */
      static int
      load_sign(const std::vector<double> &loads);

      /** The torques of the states [N m] whatever Control says (the Torque
       * list or the torque cycle): the analytical model is torque-controlled
       * and ignores Control and Rotation. */
      std::vector<double>
      torque_values() const
      {
        return torque_cycle ? cycle_torques() : torques;
      }

      /** The load values of the states: torques [N m] (the Torque list or
       * the torque cycle), or rotations [rad] under rotation control. */
      std::vector<double>
      load_values() const
      {
        if (torque_cycle)
          return cycle_torques();
        if (!rotation_control)
          return torques;
        std::vector<double> r;
        for (const double d : rotations_deg)
          r.push_back(d * dealii::numbers::PI / 180.);
        return r;
      }
      /** Crank angle of a single state, and start of a phase sweep
       * [degrees]. */
      double crank_angle_deg = 0.;
      /** Crank angle of a single state [rad]. */
      double
      crank_angle() const
      {
        return crank_angle_deg * dealii::numbers::PI / 180.;
      }

      /** Number of crank angles over one mesh period (1: only
       * `Crank angle`). */
      unsigned int n_phases = 1;

      /** Phase sweeps: MPI ranks per phase group, each group solving its
       * own block of phases (0: all ranks in one group). */
      unsigned int ranks_per_phase_group = 0;

      /** Declare subsection `Loading`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsection `Loading`. */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /** The crank angles [rad] of the states, given the mesh period
       * 2 pi / zp. */
      std::vector<double>
      crank_angles(const double mesh_period) const;
    };
  } // namespace parameters
} // namespace cycloid

#endif

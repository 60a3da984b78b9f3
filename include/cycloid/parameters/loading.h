#ifndef cycloid_parameters_loading_h
#define cycloid_parameters_loading_h

#include <deal.II/base/numbers.h>
#include <deal.II/base/parameter_handler.h>

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
      /** The load values of the states: torques [N m], or rotations
       * [rad] under rotation control. */
      std::vector<double>
      load_values() const
      {
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
      /** Number of crank angles over one mesh period (1: only
       * `Crank angle`). */
      unsigned int n_phases = 1;

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

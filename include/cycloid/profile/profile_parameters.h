#ifndef cycloid_profile_profile_parameters_h
#define cycloid_profile_profile_parameters_h

#include <deal.II/base/parameter_handler.h>

namespace cycloid
{
  /**
   * The profile for CAD and manufacturing (`Run = profile`): the exact
   * modified profile of one disc sampled to a chord tolerance, with its
   * bore and crank holes, and the writers of `profile.csv`, `profile.dxf`
   * and `profile.step`.
   */
  namespace profile
  {
    /**
     * @brief Subsection `Profile`: how finely the profile is written.
     */
    struct ProfileParameters
    {
      /** Smallest allowed chord tolerance [mm]: below it the polyline of
       * the seed disc grows beyond half a million vertices. */
      static constexpr double min_chord_tolerance = 1e-7;
      /** Largest allowed chord tolerance [mm]. */
      static constexpr double max_chord_tolerance = 1.;

      /** Largest distance of a chord of the polyline from the exact
       * profile [mm]; also the bound on the STEP spline's deviation. */
      double chord_tolerance = 1e-4;

      /** Declare subsection `Profile`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsection `Profile`; throws dealii::ExcMessage naming
       * `Profile/Chord tolerance` when it is out of range. */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace profile
} // namespace cycloid

#endif

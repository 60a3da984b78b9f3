#ifndef cycloid_support_crank_bearing_parameters_h
#define cycloid_support_crank_bearing_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace cycloid
{
  /**
   * How the output torque reaches the discs (doc/bearings.md): the crank
   * holes held rigidly (`rigid`, the default) or each crank hole on a
   * needle roller bearing whose rollers are nonlinear, compressive-only
   * springs (`needle`), the disc then free to translate and turn against
   * them.
   */
  namespace support
  {
    /**
     * @brief The sizes of the needle roller bearing in each crank hole,
     * with the `auto` ones resolved.
     */
    struct NeedleBearingSize
    {
      /** Rollers in one bearing [-]. */
      unsigned int n_rollers = 0;
      /** Roller diameter [mm]. */
      double roller_diameter = 0;
      /** Effective roller length, the length of its line contacts [mm]. */
      double roller_length = 0;
      /** Radial clearance: how far the eccentric moves in the crank hole,
       * in any direction, before a roller carries [mm]. */
      double clearance = 0;
      /** Radius of the circle through the roller centres [mm]. */
      double pitch_radius = 0;
    };

    /**
     * @brief Subsection `Crank bearings`: the support law of the discs and
     * the needle bearings' sizes.
     */
    struct CrankBearingParameters
    {
      /** The support law. */
      enum class Model
      {
        /** The crank-hole surfaces turn rigidly by the output rotation. */
        rigid,
        /** A needle roller bearing in every crank hole. */
        needle
      };

      /** The support law. */
      Model model = Model::rigid;
      /** Rollers per bearing; 0: auto [-]. */
      unsigned int n_rollers = 0;
      /** Roller diameter; 0: auto [mm]. */
      double roller_diameter = 0;
      /** Roller length; 0: auto [mm]. */
      double roller_length = 0;
      /** Radial clearance [um]. */
      double radial_clearance = 0;

      /** Declare the subsection. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);
      /** Read the subsection. */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /** Whether the discs ride on needle bearings. */
      bool
      needle() const
      {
        return model == Model::needle;
      }

      /**
       * The sizes with `auto` resolved for a crank hole of radius
       * @p hole_radius [mm] in a disc of width @p disc_width [mm]: rollers
       * of a quarter of the hole radius running on the bore, as many as a
       * cage with 25 % between neighbours holds, as long as the disc is
       * wide. Throws if the rollers do not fit the hole.
       */
      NeedleBearingSize
      size(const double hole_radius, const double disc_width) const;
    };
  } // namespace support
} // namespace cycloid

#endif

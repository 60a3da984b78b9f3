#include <deal.II/base/exceptions.h>

#include <cycloid/profile/profile_parameters.h>

#include <sstream>

namespace cycloid
{
  namespace profile
  {
    void
    ProfileParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Profile");
      {
        // The pattern accepts any number so that an out-of-range value
        // gets the explicit message of parse_parameters().
        prm.declare_entry(
          "Chord tolerance",
          "1e-4",
          dealii::Patterns::Double(),
          "Run = profile: largest distance of each chord of the written "
          "polyline from the exact modified profile [mm], 1e-7 to 1 "
          "(default 1e-4 mm = 0.1 um). The STEP spline keeps within it "
          "too.");
      }
      prm.leave_subsection();
    }



    void
    ProfileParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Profile");
      chord_tolerance = prm.get_double("Chord tolerance");
      prm.leave_subsection();
      std::ostringstream msg;
      msg << "Profile/Chord tolerance must lie in [" << min_chord_tolerance
          << ", " << max_chord_tolerance << "] mm, got " << chord_tolerance
          << " mm.";
      AssertThrow(chord_tolerance >= min_chord_tolerance &&
                    chord_tolerance <= max_chord_tolerance,
                  dealii::ExcMessage(msg.str()));
    }
  } // namespace profile
} // namespace cycloid

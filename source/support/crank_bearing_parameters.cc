#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>

#include <cycloid/parameters/or_auto.h>
#include <cycloid/support/crank_bearing_parameters.h>

#include <cmath>

namespace cycloid
{
  namespace support
  {
    void
    CrankBearingParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii::Patterns;
      using parameters::OrAuto;
      prm.enter_subsection("Crank bearings");
      {
        prm.declare_entry(
          "Model",
          "rigid",
          Selection("rigid|needle"),
          "How the output torque reaches the discs. rigid: the crank-hole "
          "surfaces turn rigidly by the output rotation (each disc welded to "
          "a rigid carrier); needle: each crank hole holds a needle roller "
          "bearing on a rigid eccentric that the locked crankshaft holds, "
          "its rollers compressive-only springs after Palmgren, so each disc "
          "also translates and turns against its bearings "
          "(doc/bearings.md). The analytic and reduced models only, so far.");
        prm.declare_entry("Number of rollers",
                          "auto",
                          OrAuto(Integer(3, 200)),
                          "Crank bearings = needle: rollers per bearing [-], "
                          "3 to 200. auto: as many as fit on the pitch "
                          "circle with a quarter of a diameter between "
                          "neighbours.");
        prm.declare_entry("Roller diameter",
                          "auto",
                          OrAuto(Double(0.1, 100)),
                          "Crank bearings = needle: roller diameter [mm], "
                          "0.1 to 100. auto: a quarter of the crank hole "
                          "radius; the rollers run directly on the bore.");
        prm.declare_entry("Roller length",
                          "auto",
                          OrAuto(Double(0.1, 1000)),
                          "Crank bearings = needle: effective length of each "
                          "roller's line contacts [mm], 0.1 to 1000. auto: "
                          "the disc width (Geometry/Tooth width).");
        prm.declare_entry(
          "Radial clearance",
          "0",
          Double(0, 1000),
          "Crank bearings = needle: how far the eccentric moves in the crank "
          "hole, in any direction, before a roller carries [um], 0 to 1000.");
      }
      prm.leave_subsection();
    }



    void
    CrankBearingParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Crank bearings");
      {
        model = prm.get("Model") == "needle" ? Model::needle : Model::rigid;
        const auto read = [&prm](const std::string &name) {
          const std::string text = prm.get(name);
          return parameters::is_auto(text) ?
                   0. :
                   dealii::Utilities::string_to_double(text);
        };
        n_rollers        = static_cast<unsigned int>(read("Number of rollers"));
        roller_diameter  = read("Roller diameter");
        roller_length    = read("Roller length");
        radial_clearance = prm.get_double("Radial clearance");
      }
      prm.leave_subsection();
    }



    NeedleBearingSize
    CrankBearingParameters::size(const double hole_radius,
                                 const double disc_width) const
    {
      NeedleBearingSize s;
      s.roller_diameter =
        roller_diameter > 0 ? roller_diameter : 0.25 * hole_radius;
      s.roller_length = roller_length > 0 ? roller_length : disc_width;
      s.clearance     = 1e-3 * radial_clearance;
      s.pitch_radius  = hole_radius - 0.5 * s.roller_diameter;
      AssertThrow(s.roller_diameter < hole_radius,
                  dealii::ExcMessage(
                    "Crank bearings/Roller diameter (" +
                    dealii::Utilities::to_string(s.roller_diameter) +
                    " mm) must be smaller than Geometry/Crank hole radius (" +
                    dealii::Utilities::to_string(hole_radius) +
                    " mm): the eccentric must fit inside the rollers."));
      // Rollers touch when their centres are one diameter apart on the
      // pitch circle.
      const unsigned int fit = static_cast<unsigned int>(std::floor(
        dealii::numbers::PI /
        std::asin(std::min(1., 0.5 * s.roller_diameter / s.pitch_radius))));
      s.n_rollers            = n_rollers > 0 ?
                                 n_rollers :
                                 static_cast<unsigned int>(
                        std::floor(2. * dealii::numbers::PI * s.pitch_radius /
                                   (1.25 * s.roller_diameter)));
      AssertThrow(s.n_rollers <= fit && s.n_rollers >= 3,
                  dealii::ExcMessage(
                    "Crank bearings/Number of rollers = " +
                    std::to_string(s.n_rollers) + ": " + std::to_string(fit) +
                    " rollers of diameter " +
                    dealii::Utilities::to_string(s.roller_diameter) +
                    " mm fit in a crank hole of radius " +
                    dealii::Utilities::to_string(hole_radius) +
                    " mm, and a bearing needs at least 3."));
      return s;
    }
  } // namespace support
} // namespace cycloid

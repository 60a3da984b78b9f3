// Parameter validation: each impossible input ends with an error that names
// the parameter (or the cause), and the defaults are the seed case.

#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/parameter_handler.h>

#include <cycloid/analytic/stage_model.h>
#include <cycloid/app/all_parameters.h>
#include <cycloid/app/parameter_suggestions.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

using namespace cycloid;

namespace
{
  /** Parse @p text, build the model; return the error text ("" if none). */
  std::string
  error_of(const std::string &text)
  {
    try
      {
        dealii::ParameterHandler prm;
        app::AllParameters::declare_parameters(prm);
        prm.parse_input_from_string(text);
        app::AllParameters p;
        p.parse_parameters(prm);
        const analytic::StageModel model(p.model_settings());
      }
    catch (dealii::ExceptionBase &e)
      {
        std::ostringstream s;
        e.print_info(s);
        return s.str();
      }
    return "";
  }

  std::string
  geometry_section(const std::string &entries)
  {
    return "subsection Geometry\n" + entries + "\nend\n";
  }
} // namespace



TEST(Parameters, DefaultsAreTheSeedCase)
{
  EXPECT_EQ(error_of(""), "");
  dealii::ParameterHandler prm;
  app::AllParameters::declare_parameters(prm);
  app::AllParameters p;
  p.parse_parameters(prm);
  EXPECT_EQ(p.geometry.n_pins, 40u);
  EXPECT_EQ(p.geometry.n_teeth, 39u);
  EXPECT_DOUBLE_EQ(p.geometry.pin_radius, 3.);
  EXPECT_DOUBLE_EQ(p.geometry.eccentricity, 2.2);
  EXPECT_DOUBLE_EQ(p.geometry.shortening_coefficient, 0.675);
  EXPECT_DOUBLE_EQ(p.geometry.tooth_width, 16.);
  EXPECT_DOUBLE_EQ(p.material.disc.youngs_modulus, 212000.);
  EXPECT_DOUBLE_EQ(p.material.housing.youngs_modulus, 173000.);
  EXPECT_DOUBLE_EQ(p.material.pin.poissons_ratio, 0.3);
}



TEST(Parameters, ImpossibleGeometryNamesTheParameter)
{
  const struct
  {
    std::string entries, expected;
  } cases[] = {
    {"set Shortening coefficient = 1", "Shortening coefficient"},
    {"set Shortening coefficient = 0", "Shortening coefficient"},
    {"set Shortening coefficient = 1.2", "Shortening coefficient"},
    {"set Number of cycloid teeth = 40", "Number of cycloid teeth"},
    {"set Number of cycloid teeth = 38", "Number of cycloid teeth"},
    {"set Pin radius = 0", "Pin radius"},
    {"set Pin radius = -1", "Pin radius"},
    {"set Eccentricity = 0", "Eccentricity"},
    {"set Tooth width = 0", "Tooth width"},
    {"set Pin radius = 10.5", "neighbouring pins overlap"},
    {"set Pin radius = 6\nset Shortening coefficient = 0.9", "undercuts"},
    {"set Pin circle radius modification = 0.01", "overlap a pin at rest"},
    {"set Pin radius modification = -0.005", "overlap a pin at rest"},
    {"set Rotation modification = 0.01", "overlap a pin at rest"},
    {"set Bore radius = 126", "Bore radius"},
    {"set Crank hole radius = 45", "Crank hole"},
    {"set Crank hole circle radius = 115", "Crank hole"},
  };
  for (const auto &c : cases)
    {
      const std::string err = error_of(geometry_section(c.entries));
      EXPECT_NE(err.find(c.expected), std::string::npos)
        << "input '" << c.entries << "' gave: '" << err << "'";
    }
}



TEST(Parameters, BadMaterialsAndLoadsNameTheParameter)
{
  const struct
  {
    std::string text, expected;
  } cases[] = {
    {"subsection Material\nset Disc Poisson's ratio = 0.5\nend",
     "Poisson's ratio"},
    {"subsection Material\nset Pin Poisson's ratio = -1\nend",
     "Poisson's ratio"},
    {"subsection Material\nset Pin Young's modulus = 0\nend",
     "Young's modulus"},
    {"subsection Material\nset Housing Young's modulus = -5\nend",
     "Housing Young's modulus"},
    {"subsection Loading\nset Torque = abc\nend", "Torque"},
    {"subsection Scene\nset Pins = soft\nend", "Pins"},
    {"set Run = fast", "Run"},
    {"subsection Scene\nset Pin core radius = 3\nend", "Pin core radius"},
  };
  for (const auto &c : cases)
    {
      const std::string err = error_of(c.text);
      EXPECT_NE(err.find(c.expected), std::string::npos)
        << "input '" << c.text << "' gave: '" << err << "'";
    }
}



TEST(Parameters, ModificationsWithClearanceAreAccepted)
{
  EXPECT_EQ(error_of(
              geometry_section("set Pin circle radius modification = 0.01\n"
                               "set Pin radius modification = 0.01")),
            "");
  EXPECT_EQ(error_of(
              geometry_section("set Pin circle radius modification = -0.01\n"
                               "set Pin radius modification = 0.01\n"
                               "set Rotation modification = 0.003")),
            "");
}



TEST(Parameters, PhaseSweepCoversOneClosedPeriod)
{
  parameters::LoadingParameters l;
  l.n_phases        = 5;
  l.crank_angle_deg = 1.;
  const auto a      = l.crank_angles(0.25);
  ASSERT_EQ(a.size(), 5u);
  EXPECT_NEAR(a.back() - a.front(), 0.25, 1e-15);
  EXPECT_NEAR(a.front(), 1. * dealii::numbers::PI / 180., 1e-12);
}



TEST(Parameters, ClosestNamesAreSuggested)
{
  using D = app::DeclaredParameters;
  const std::vector<std::string> entries{"Tooth width",
                                         "Pin radius",
                                         "Pin radius modification",
                                         "Pin circle radius modification"};
  // A transposition is one typo; the case does not count.
  EXPECT_EQ(D::closest("Tooth widht", entries),
            std::vector<std::string>{"Tooth width"});
  EXPECT_EQ(D::closest("pin radius", entries).front(), "Pin radius");
  EXPECT_EQ(D::closest("Pin radius", entries),
            (std::vector<std::string>{"Pin radius",
                                      "Pin radius modification"}));
  EXPECT_TRUE(D::closest("Xyzzy", entries).empty());
  EXPECT_EQ(D::closest("Geometri", {"Material", "Geometry", "Loading"}),
            std::vector<std::string>{"Geometry"});
}



TEST(Parameters, MisspelledLinesAreExplained)
{
  const std::string file = "test_parameters_misspelled.prm";
  std::ofstream("test_parameters_misspelled.prm")
    << "# a comment\n"
       "subsection Geometry\n"
       "  set Number of pins = \\\n"
       "    40\n"
       "  set Torque = 3\n"
       "end\n"
       "set Run = analytc\n";
  dealii::ParameterHandler prm;
  app::AllParameters::declare_parameters(prm);
  const app::DeclaredParameters declared(prm);
  // Line 3 continues on line 4, which deal.II counts as line 3.
  EXPECT_EQ(declared.explain_line(file, 3), "");
  EXPECT_EQ(declared.explain_line(file, 5),
            "there is no entry 'Torque' in subsection 'Geometry'; 'Torque' "
            "is declared in subsection 'Loading'");
  EXPECT_NE(declared.explain_line(file, 7).find("did you mean 'analytic'?"),
            std::string::npos);
  std::remove(file.c_str());
}

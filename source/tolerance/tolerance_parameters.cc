#include <cycloid/tolerance/tolerance_parameters.h>

namespace cycloid
{
  namespace tolerance
  {
    void
    ToleranceParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii::Patterns;
      prm.enter_subsection("Tolerance study");
      {
        prm.declare_entry(
          "Model",
          "reduced",
          Selection("reduced|analytic"),
          "Run = tolerance: the model that solves every sample. reduced: "
          "the reduced model, condensed once for the nominal stage and "
          "reused for every sample (FE accuracy; doc/tolerance.md); "
          "analytic: the analytical model (seconds for thousands of "
          "samples, its pair stiffness an approximation).");
        prm.declare_entry("Number of samples",
                          "1000",
                          Integer(0, 10000000),
                          "Run = tolerance: random samples of the stage, "
                          "beyond the nominal one (sample 0) [-], 0 to 1e7. "
                          "10 000 give P95 to about +-0.5 %.");
        prm.declare_entry(
          "Random seed",
          "1",
          Integer(0, 2147483647),
          "Run = tolerance: seed of the random draws [-]; sample s is drawn "
          "from the seed and s alone, so the same seed gives the same "
          "samples on any number of ranks.");
        prm.declare_entry(
          "Distribution",
          "normal",
          Selection("normal|uniform"),
          "Run = tolerance: how each deviation spreads over its band. "
          "normal: the band is +-3 sigma (a pin centre: each coordinate "
          "with sigma = diameter / 6); uniform: evenly over the band (a "
          "pin centre: evenly over the true-position circle).");
        prm.declare_entry(
          "Pin position tolerance",
          "0",
          Double(0, 1000),
          "Run = tolerance: diameter of the true-position circle (ISO "
          "1101) each pin centre lies in [um], 0 to 1000.");
        prm.declare_entry("Pin radius tolerance",
                          "0",
                          Double(0, 1000),
                          "Run = tolerance: +- band of each pin's radius "
                          "[um], 0 to 1000.");
        prm.declare_entry("Eccentricity tolerance",
                          "0",
                          Double(0, 1000),
                          "Run = tolerance: +- band of each disc's "
                          "eccentricity (its crank eccentric) [um], 0 to "
                          "1000.");
        prm.declare_entry("Disc angle tolerance",
                          "0",
                          Double(0, 600),
                          "Run = tolerance: +- band of each disc's angular "
                          "placement (index error of its crank holes) "
                          "[arcmin], 0 to 600.");
        prm.declare_entry(
          "Profile tolerance",
          "0",
          Double(0, 1000),
          "Run = tolerance: +- band of each disc's own Delta rp and Delta "
          "rrp (each drawn on its own) [um], 0 to 1000.");
        prm.declare_entry(
          "Sensitivity",
          "true",
          Bool(),
          "Run = tolerance: also solve the samples once per band with that "
          "band alone (the same draws), for each band's share of the "
          "variance of K, rotation and peak pin force "
          "(tolerance_sensitivity.csv); costs one more study per band "
          "wider than zero.");
      }
      prm.leave_subsection();
    }



    void
    ToleranceParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Tolerance study");
      {
        model =
          prm.get("Model") == "reduced" ? Model::reduced : Model::analytic;
        n_samples    = prm.get_integer("Number of samples");
        seed         = prm.get_integer("Random seed");
        distribution = prm.get("Distribution") == "normal" ?
                         Distribution::normal :
                         Distribution::uniform;
        pin_position = prm.get_double("Pin position tolerance");
        pin_radius   = prm.get_double("Pin radius tolerance");
        eccentricity = prm.get_double("Eccentricity tolerance");
        disc_angle   = prm.get_double("Disc angle tolerance");
        profile      = prm.get_double("Profile tolerance");
        sensitivity  = prm.get_bool("Sensitivity");
      }
      prm.leave_subsection();
    }
  } // namespace tolerance
} // namespace cycloid

#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>

#include <cycloid/parameters/loading.h>
#include <cycloid/parameters/material.h>
#include <cycloid/parameters/run.h>
#include <cycloid/parameters/scene.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

namespace cycloid
{
  namespace parameters
  {
    namespace
    {
      void
      declare_material(dealii::ParameterHandler &prm,
                       const std::string        &body,
                       const ElasticMaterial    &defaults)
      {
        using dealii::Patterns::Double;
        prm.declare_entry(body + " Young's modulus",
                          dealii::Utilities::to_string(defaults.youngs_modulus),
                          Double(0),
                          "Young's modulus of the " + body + " [MPa].");
        prm.declare_entry(body + " Poisson's ratio",
                          dealii::Utilities::to_string(defaults.poissons_ratio),
                          Double(-1, 0.5),
                          "Poisson's ratio of the " + body +
                            " [-], in (-1, 0.5).");
        prm.declare_entry(body + " density",
                          dealii::Utilities::to_string(defaults.density),
                          Double(0),
                          "Density of the " + body + " [kg/m^3].");
      }

      ElasticMaterial
      parse_material(dealii::ParameterHandler &prm, const std::string &body)
      {
        ElasticMaterial m;
        m.youngs_modulus = prm.get_double(body + " Young's modulus");
        m.poissons_ratio = prm.get_double(body + " Poisson's ratio");
        m.density        = prm.get_double(body + " density");
        AssertThrow(m.youngs_modulus > 0,
                    dealii::ExcMessage("Material/" + body +
                                       " Young's modulus must be positive."));
        AssertThrow(m.poissons_ratio > -1 && m.poissons_ratio < 0.5,
                    dealii::ExcMessage("Material/" + body +
                                       " Poisson's ratio must lie in "
                                       "(-1, 0.5), got " +
                                       std::to_string(m.poissons_ratio) + "."));
        AssertThrow(m.density > 0,
                    dealii::ExcMessage("Material/" + body +
                                       " density must be positive."));
        return m;
      }
    } // namespace



    void
    MaterialParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      const MaterialParameters defaults;
      prm.enter_subsection("Material");
      declare_material(prm, "Disc", defaults.disc);
      declare_material(prm, "Pin", defaults.pin);
      declare_material(prm, "Housing", defaults.housing);
      prm.declare_entry(
        "Allowable contact pressure",
        dealii::Utilities::to_string(defaults.allowable_contact_pressure),
        dealii::Patterns::Double(0.),
        "Peak contact pressure of a pin above which a run warns, naming "
        "the pin and the state [MPa], >= 0; 0: never. Default 1500 MPa: "
        "the contact fatigue limit sigma_Hlim of case-hardened steels such "
        "as the 20CrMnTi of discs and pins (ISO 6336-5, about 1300 to "
        "1650 MPa by quality grade).");
      prm.leave_subsection();
    }



    void
    MaterialParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Material");
      disc                       = parse_material(prm, "Disc");
      pin                        = parse_material(prm, "Pin");
      housing                    = parse_material(prm, "Housing");
      allowable_contact_pressure = prm.get_double("Allowable contact pressure");
      prm.leave_subsection();
    }



    void
    LoadingParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii::Patterns;
      prm.enter_subsection("Loading");
      {
        prm.declare_entry("Torque",
                          "1000",
                          List(Double(-1e9, 1e9), 1),
                          "Output torque of the whole stage [N m]; a "
                          "comma-separated list is a torque sweep, solved in "
                          "the given order at every crank angle.");
        prm.declare_entry("Control",
                          "torque",
                          Selection("torque|rotation"),
                          "FE runs: prescribe the output torque (Torque; "
                          "the rotation beta follows) or the rotation of the "
                          "discs' load surfaces (Rotation; the reaction "
                          "torque follows).");
        prm.declare_entry("Rotation",
                          "0.01",
                          List(Double(-10, 10), 1),
                          "Rotations beta of the discs' load surfaces for "
                          "Control = rotation [degrees]; a list is solved in "
                          "order.");
        prm.declare_entry("Crank angle",
                          "0",
                          Double(-3600, 3600),
                          "Crank angle psi of a single state, and the first "
                          "angle of a phase sweep [degrees].");
        prm.declare_entry("Number of phases",
                          "1",
                          Integer(1, 100000),
                          "Number of crank angles of a phase sweep over one "
                          "mesh period 360/zp degrees, both ends included "
                          "[-]; 1 solves only at Crank angle.");
        prm.declare_entry("Ranks per phase group",
                          "0",
                          Integer(0, 100000),
                          "Phase sweeps: MPI ranks per phase group [ranks]. "
                          "The ranks split into groups of this size, each "
                          "solving a contiguous block of the phases on its "
                          "own ranks (the number of ranks must be a multiple, "
                          "with at most one group per phase); 0 puts all "
                          "ranks in one group. Other run modes ignore it.");
        prm.declare_entry("Rated torque",
                          "1000",
                          Double(1e-6, 1e9),
                          "Rated output torque of the catalogue torque cycle "
                          "[N m] (the reducer's catalogue value; > 0).");
        prm.declare_entry("Torque cycle",
                          "false",
                          Bool(),
                          "Solve the catalogue cycle 0 -> +Rated -> -Rated -> "
                          "0 instead of the Torque list (analytic, "
                          "quasi-static and phase-sweep runs), and write "
                          "torsion_curve.csv and rigidity.csv.");
        prm.declare_entry("Torque cycle steps",
                          "40",
                          Integer(4, 100000),
                          "Steps of the torque cycle, a multiple of 4 (one "
                          "quarter per branch) [-]; the +-3 % and +-50 % "
                          "states the catalogue figures read are added where "
                          "the steps miss them.");
      }
      prm.leave_subsection();
    }



    void
    LoadingParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Loading");
      {
        torques = dealii::Utilities::string_to_double(
          dealii::Utilities::split_string_list(prm.get("Torque")));
        crank_angle_deg  = prm.get_double("Crank angle");
        rotation_control = prm.get("Control") == "rotation";
        rotations_deg    = dealii::Utilities::string_to_double(
          dealii::Utilities::split_string_list(prm.get("Rotation")));
        n_phases              = prm.get_integer("Number of phases");
        ranks_per_phase_group = prm.get_integer("Ranks per phase group");
        rated_torque          = prm.get_double("Rated torque");
        torque_cycle          = prm.get_bool("Torque cycle");
        torque_cycle_steps    = prm.get_integer("Torque cycle steps");
      }
      prm.leave_subsection();
      AssertThrow(!torques.empty(),
                  dealii::ExcMessage("Loading/Torque: give at least one "
                                     "torque."));
      AssertThrow(!torque_cycle || torque_cycle_steps % 4 == 0,
                  dealii::ExcMessage(
                    "Loading/Torque cycle steps = " +
                    std::to_string(torque_cycle_steps) +
                    " is not a multiple of 4 (one quarter per branch of the "
                    "cycle 0 -> +Rated -> 0 -> -Rated -> 0)."));
      AssertThrow(!(torque_cycle && rotation_control),
                  dealii::ExcMessage(
                    "Loading/Torque cycle = true needs Loading/Control = "
                    "torque: the catalogue cycle prescribes torques."));
    }



    std::vector<double>
    LoadingParameters::cycle_torques() const
    {
      // One branch 0 -> 1 as fractions of the rated torque: the equal
      // steps and the catalogue's reading points.
      const unsigned int  q = torque_cycle_steps / 4;
      std::vector<double> branch{0., lost_motion_torque, 0.5};
      for (unsigned int i = 1; i <= q; ++i)
        branch.push_back(double(i) / q);
      std::sort(branch.begin(), branch.end());
      branch.erase(std::unique(branch.begin(),
                               branch.end(),
                               [](const double a, const double b) {
                                 return std::abs(a - b) < 1e-12;
                               }),
                   branch.end());
      std::vector<double> loads;
      for (const double sign : {1., -1.})
        {
          for (const double f : branch) // up
            loads.push_back(sign * f * rated_torque);
          for (auto f = std::next(branch.rbegin()); f != branch.rend(); ++f)
            loads.push_back(sign * *f * rated_torque); // back down to zero
        }
      return loads;
    }



    int
    LoadingParameters::zero_side(const std::vector<double> &loads,
                                 const unsigned int         i)
    {
      const double towards = (i > 0 && loads[i - 1] != 0) ? loads[i - 1] :
                             i + 1 < loads.size()         ? loads[i + 1] :
                                                            1.;
      return towards >= 0 ? 1 : -1;
    }



    int
    LoadingParameters::load_sign(const std::vector<double> &loads)
    {
      bool positive = false, negative = false;
      for (const double t : loads)
        {
          positive |= t > 0;
          negative |= t < 0;
        }
      return positive && negative ? 0 : (negative ? -1 : 1);
    }



    std::vector<double>
    LoadingParameters::crank_angles(const double mesh_period) const
    {
      const double        psi0 = crank_angle_deg * dealii::numbers::PI / 180.;
      std::vector<double> angles;
      if (n_phases == 1)
        return {psi0};
      for (unsigned int k = 0; k < n_phases; ++k)
        angles.push_back(psi0 + mesh_period * k / (n_phases - 1));
      return angles;
    }



    void
    SceneParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii::Patterns;
      prm.enter_subsection("Scene");
      {
        prm.declare_entry("Dimension",
                          "2",
                          Integer(2, 3),
                          "Spatial dimension of an FE scene: 2 (plane strain, "
                          "results scaled to the tooth width) or 3.");
        prm.declare_entry("Number of discs",
                          "auto",
                          Selection("auto|1|2"),
                          "Number of cycloid discs: 2 (the RV stage, discs "
                          "half a turn apart), 1, or auto: 1 in a 2D FE run "
                          "(mesh, quasi-static, phase-sweep, transient; plane "
                          "strain models one disc), 2 otherwise (the "
                          "analytical model, 3D scenes).");
        prm.declare_entry("Pins",
                          "elastic",
                          Selection("elastic|rigid"),
                          "Pin model: elastic bodies or rigid cylinders.");
        prm.declare_entry("Pin support",
                          "axis",
                          Selection("axis|housing"),
                          "What holds the pins: 'axis' (a rigid core of "
                          "radius Pin core radius around each pin axis is "
                          "held fixed) or 'housing' (pins seated in the "
                          "housing grooves).");
        prm.declare_entry("Pin core radius",
                          "0.5",
                          Double(0),
                          "Radius of the rigid core held fixed around each "
                          "pin axis for Pin support = axis [mm].");
        prm.declare_entry("Load introduction",
                          "crank holes",
                          Selection("bore|crank holes"),
                          "Disc surfaces that turn rigidly by the load "
                          "rotation beta about the disc centre.");
      }
      prm.leave_subsection();
    }



    void
    SceneParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Scene");
      {
        dimension    = prm.get_integer("Dimension");
        n_discs_auto = prm.get("Number of discs") == "auto";
        n_discs      = n_discs_auto ? 2 : prm.get_integer("Number of discs");
        pins = prm.get("Pins") == "rigid" ? PinModel::rigid : PinModel::elastic;
        pin_support       = prm.get("Pin support") == "housing" ?
                              PinSupport::housing :
                              PinSupport::axis;
        pin_core_radius   = prm.get_double("Pin core radius");
        load_introduction = prm.get("Load introduction") == "bore" ?
                              LoadIntroduction::bore :
                              LoadIntroduction::crank_holes;
      }
      prm.leave_subsection();
    }



    std::string
    SceneParameters::resolve_number_of_discs(const bool fe_run)
    {
      if (!n_discs_auto || !fe_run || dimension != 2)
        return "";
      n_discs = 1;
      return "2D FE: one disc (Scene/Number of discs = auto)";
    }



    const std::vector<RunParameters::ModeEntry> &
    RunParameters::modes()
    {
      static const std::vector<ModeEntry> table = {
        {Mode::analytic,
         "analytic",
         "Hertz-based load distribution over the pins, Analytic subsection"},
        {Mode::reduced,
         "reduced",
         "the coarse FE compliance condensed onto the contacts with the "
         "analytic line-contact law (near FE accuracy at a fraction of its "
         "cost), Reduced subsection; driven like 'analytic' by the Torque "
         "list and crank angles"},
        {Mode::tolerance,
         "tolerance",
         "a Monte-Carlo study of the stage under manufacturing tolerances "
         "(reduced or analytic model, the nominal compliance reused for "
         "every sample), Tolerance study subsection"},
        {Mode::quasi_static,
         "quasi-static",
         "FE contact at Crank angle, for the torque(s)"},
        {Mode::phase_sweep, "phase-sweep", "FE contact over Number of phases"},
        {Mode::transient, "transient", "elastodynamics with contact"},
        {Mode::mesh, "mesh", "write the FE mesh of the scene"},
        {Mode::profile,
         "profile",
         "the modified profile of one disc as profile.csv, .dxf and .step "
         "for CAD, at Profile/Chord tolerance"}};
      return table;
    }



    std::string
    RunParameters::mode_help()
    {
      std::string text;
      for (const auto &m : modes())
        {
          std::string name = m.name;
          name.resize(14, ' ');
          text += "  " + name + m.summary + "\n";
        }
      return text;
    }



    void
    RunParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii::Patterns;
      std::string names, text = "Run mode: ";
      for (const auto &m : modes())
        {
          names += (names.empty() ? "" : "|") + std::string(m.name);
          text += std::string(m.mode == modes().front().mode ? "" : "; ") +
                  "'" + m.name + "' (" + m.summary + ")";
        }
      prm.declare_entry("Run", "analytic", Selection(names), text + ".");
      prm.declare_entry("Output directory",
                        "output",
                        Anything(),
                        "Directory for the results (created if missing).");
      prm.declare_entry("Write solution",
                        "true",
                        Bool(),
                        "FE runs: write solution-NNNN.pvtu (+ solution.pvd) "
                        "for every solved state (3D fields take tens of MB a "
                        "state; the CSV files are always written).");
    }



    void
    RunParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      mode_name        = prm.get("Run");
      output_directory = prm.get("Output directory");
      write_solution   = prm.get_bool("Write solution");
      AssertThrow(!output_directory.empty(),
                  dealii::ExcMessage("Output directory must not be empty."));
      // The Selection pattern admits only the table's names.
      for (const auto &m : modes())
        if (mode_name == m.name)
          mode = m.mode;
    }



  } // namespace parameters
} // namespace cycloid

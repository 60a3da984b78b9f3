#include <cycloid/app/ignored_entries.h>

#include <algorithm>
#include <functional>

namespace cycloid
{
  namespace app
  {
    namespace
    {
      using Mode = parameters::RunParameters::Mode;

      /** A set of run modes. */
      using Modes = std::vector<Mode>;

      /** One row of the table: the entries (a name, or "Subsection/" and an
       * asterisk for the whole subsection) that the modes do not read, when. */
      struct Rule
      {
        /** "Subsection/Entry", or "Subsection/" and an asterisk. */
        std::string entries;
        /** The modes that ignore them. */
        Modes modes;
        /** Why, for the warning. */
        std::string reason;
        /** Further condition on the run (none: always). */
        std::function<bool(const RunShape &)> when = nullptr;
      };

      /** A 2D scene (no axial layers, one disc). */
      bool
      two_d(const RunShape &s)
      {
        return s.dimension == 2;
      }

      /** A mesh that does not depend on the loads' sign. */
      bool
      unsigned_mesh(const RunShape &s)
      {
        return !s.refine_loaded_side_only;
      }

      /** The discs on rigid crank holes. */
      bool
      rigid_supports(const RunShape &s)
      {
        return !s.needle_bearings;
      }

      const Modes all_modes{Mode::analytic,
                            Mode::mesh,
                            Mode::quasi_static,
                            Mode::phase_sweep,
                            Mode::transient,
                            Mode::reduced,
                            Mode::tolerance,
                            Mode::profile};

      const Modes fe_modes{Mode::mesh,
                           Mode::quasi_static,
                           Mode::phase_sweep,
                           Mode::transient,
                           Mode::reduced,
                           Mode::tolerance};

      /**
       * Which run mode ignores what. The rule of thumb: `analytic` reads
       * Geometry, Material, Loading (not Control/Rotation), Scene/Number
       * of discs, Pins, Load introduction, and Analytic; `profile` reads
       * only Geometry and Profile; `mesh` reads Geometry, Scene and Mesh
       * (and the loads' sign for Contact refinement side = loaded); the FE
       * solves read everything but the other modes' subsections and
       * Number of phases (quasi-static, transient) or the torque cycle
       * (transient). Geometry is read by every mode, since every mode
       * checks it (CycloidGeometry). Keep this table in step with what the
       * runs read (tests/test_parameters.cc checks some rows).
       */
      const std::vector<Rule> &
      rules()
      {
        static const std::vector<Rule> table{
          {"Write solution",
           {Mode::analytic,
            Mode::mesh,
            Mode::profile,
            Mode::reduced,
            Mode::tolerance},
           "it writes no FE fields"},
          {"Material/*", {Mode::mesh, Mode::profile}, "it solves nothing"},
          {"Loading/*", {Mode::profile}, "it only draws the profile"},
          {"Loading/Control",
           {Mode::analytic},
           "the analytic model is torque-controlled"},
          {"Loading/Rotation",
           {Mode::analytic},
           "the analytic model is torque-controlled"},
          {"Loading/Control",
           {Mode::reduced, Mode::tolerance},
           "the reduced model is torque-controlled"},
          {"Loading/Rotation",
           {Mode::reduced, Mode::tolerance},
           "the reduced model is torque-controlled"},
          {"Loading/Number of phases",
           {Mode::quasi_static},
           "it solves at Loading/Crank angle only; Run = phase-sweep sweeps "
           "the phases"},
          {"Loading/Number of phases",
           {Mode::transient},
           "the crank turns at Transient/Crank speed"},
          {"Loading/Number of phases",
           {Mode::mesh},
           "it meshes the stage at Loading/Crank angle"},
          {"Loading/Rated torque",
           {Mode::transient, Mode::mesh},
           "it runs no torque cycle"},
          {"Loading/Torque cycle steps",
           {Mode::transient, Mode::mesh},
           "it runs no torque cycle"},
          {"Loading/Torque", {Mode::mesh}, "it solves nothing", unsigned_mesh},
          {"Loading/Control", {Mode::mesh}, "it solves nothing", unsigned_mesh},
          {"Loading/Rotation",
           {Mode::mesh},
           "it solves nothing",
           unsigned_mesh},
          {"Loading/Torque cycle",
           {Mode::mesh},
           "it solves nothing",
           unsigned_mesh},
          {"Scene/*", {Mode::profile}, "it only draws the profile"},
          {"Scene/Dimension",
           {Mode::analytic},
           "the analytic model has no FE scene"},
          {"Scene/Pin support",
           {Mode::analytic},
           "the analytic model has no FE scene"},
          {"Scene/Pin core radius",
           {Mode::analytic},
           "the analytic model has no FE scene"},
          {"Analytic/*", {Mode::mesh, Mode::profile}, "it solves nothing"},
          {"Mesh/*", {Mode::analytic, Mode::profile}, "it makes no mesh"},
          {"Mesh/Axial layers per disc",
           fe_modes,
           "a 2D scene has no axial layers",
           two_d},
          {"Mesh/Axial layers in the gap",
           fe_modes,
           "a 2D scene has no axial layers",
           two_d},
          {"Geometry/Axial gap between discs",
           fe_modes,
           "a 2D scene has one disc",
           two_d},
          {"Contact/*",
           {Mode::analytic,
            Mode::mesh,
            Mode::profile,
            Mode::reduced,
            Mode::tolerance},
           "it solves no FE contact"},
          {"Mesh/Contact refinements",
           {Mode::reduced, Mode::tolerance},
           "its coarse model is refined by Reduced/Contact refinements"},
          {"Mesh/Contact refinement side",
           {Mode::reduced, Mode::tolerance},
           "its coarse model is refined at the loaded side of its torques"},
          {"Mesh/Adaptive refinement cycles",
           {Mode::reduced, Mode::tolerance},
           "its coarse model is not refined adaptively"},
          {"Mesh/Error estimate",
           {Mode::mesh, Mode::transient, Mode::reduced, Mode::tolerance},
           "it estimates no FE state's error (transient: one mesh through "
           "the run)"},
          {"Mesh/Warning threshold",
           {Mode::mesh, Mode::transient, Mode::reduced, Mode::tolerance},
           "it estimates no FE state's error (transient: one mesh through "
           "the run)"},
          {"Mesh/Target accuracy",
           {Mode::mesh, Mode::transient, Mode::reduced, Mode::tolerance},
           "it estimates no FE state's error (transient: one mesh through "
           "the run)"},
          {"Mesh/Maximum accuracy cycles",
           {Mode::mesh, Mode::transient, Mode::reduced, Mode::tolerance},
           "it estimates no FE state's error (transient: one mesh through "
           "the run)"},
          {"Mesh/Triangulation",
           {Mode::mesh},
           "it writes the mesh of the shared triangulation (every cell on "
           "every rank)"},
          {"Mesh/Maximum sweep refinements",
           {Mode::quasi_static,
            Mode::mesh,
            Mode::transient,
            Mode::reduced,
            Mode::tolerance},
           "only Run = phase-sweep repeats itself to resolve a fluctuation"},
          {"Mesh/Axial layers per disc",
           {Mode::reduced, Mode::tolerance},
           "its coarse model has Reduced/Axial layers per disc"},
          {"Reduced/Axial layers per disc",
           {Mode::reduced, Mode::tolerance},
           "a 2D scene has no axial layers",
           two_d},
          {"Reduced/Axial slices per disc",
           {Mode::reduced, Mode::tolerance},
           "a 2D scene has no axial slices",
           two_d},
          {"Reduced/*",
           {Mode::analytic,
            Mode::mesh,
            Mode::quasi_static,
            Mode::phase_sweep,
            Mode::transient,
            Mode::profile},
           "only Run = reduced and tolerance read it"},
          {"Solver/*",
           {Mode::analytic, Mode::mesh, Mode::profile},
           "it solves no FE contact"},
          {"Transient/*",
           {Mode::analytic,
            Mode::mesh,
            Mode::quasi_static,
            Mode::phase_sweep,
            Mode::reduced,
            Mode::tolerance,
            Mode::profile},
           "only Run = transient reads it"},
          {"Tolerance study/*",
           {Mode::analytic,
            Mode::mesh,
            Mode::quasi_static,
            Mode::phase_sweep,
            Mode::transient,
            Mode::reduced,
            Mode::profile},
           "only Run = tolerance reads it"},
          {"Crank bearings/Number of rollers",
           all_modes,
           "Crank bearings/Model = rigid holds the crank holes rigidly",
           rigid_supports},
          {"Crank bearings/Roller diameter",
           all_modes,
           "Crank bearings/Model = rigid holds the crank holes rigidly",
           rigid_supports},
          {"Crank bearings/Roller length",
           all_modes,
           "Crank bearings/Model = rigid holds the crank holes rigidly",
           rigid_supports},
          {"Crank bearings/Radial clearance",
           all_modes,
           "Crank bearings/Model = rigid holds the crank holes rigidly",
           rigid_supports},
          {"Crank bearings/*",
           {Mode::mesh, Mode::profile},
           "it solves no load state"},
          {"Profile/*",
           {Mode::analytic,
            Mode::mesh,
            Mode::quasi_static,
            Mode::phase_sweep,
            Mode::transient,
            Mode::reduced,
            Mode::tolerance},
           "only Run = profile reads it"},
        };
        return table;
      }



      /** The name of @p mode as in the parameter file. */
      std::string
      mode_name(const Mode mode)
      {
        switch (mode)
          {
            case Mode::analytic:
              return "analytic";
            case Mode::mesh:
              return "mesh";
            case Mode::quasi_static:
              return "quasi-static";
            case Mode::phase_sweep:
              return "phase-sweep";
            case Mode::transient:
              return "transient";
            case Mode::reduced:
              return "reduced";
            case Mode::tolerance:
              return "tolerance";
            case Mode::profile:
              return "profile";
          }
        return "";
      }



      /** Whether @p rule covers entry @p name in a run of shape @p shape. */
      bool
      covers(const Rule &rule, const std::string &name, const RunShape &shape)
      {
        const std::string &e = rule.entries;
        const bool all = e.size() > 2 && e.compare(e.size() - 2, 2, "/*") == 0;
        const bool matches =
          all ? name.compare(0, e.size() - 1, e, 0, e.size() - 1) == 0 :
                name == e;
        return matches &&
               std::find(rule.modes.begin(), rule.modes.end(), shape.mode) !=
                 rule.modes.end() &&
               (!rule.when || rule.when(shape));
      }
    } // namespace



    std::vector<std::string>
    ignored_entry_table()
    {
      std::vector<std::string> entries;
      for (const Rule &rule : rules())
        entries.push_back(rule.entries);
      return entries;
    }



    std::vector<std::string>
    ignored_entry_warnings(
      const RunShape                           &shape,
      const std::map<std::string, std::string> &set_in_file)
    {
      std::vector<std::string> warnings;
      for (const auto &[name, value] : set_in_file)
        for (const Rule &rule : rules())
          if (covers(rule, name, shape))
            {
              warnings.push_back(
                "warning: " + name + " = " + value + " is ignored by Run = " +
                mode_name(shape.mode) + " (" + rule.reason + ")");
              break;
            }
      return warnings;
    }
  } // namespace app
} // namespace cycloid

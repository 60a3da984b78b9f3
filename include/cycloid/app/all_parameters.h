#ifndef cycloid_app_all_parameters_h
#define cycloid_app_all_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <cycloid/analytic/analytic_parameters.h>
#include <cycloid/analytic/stage_model.h>
#include <cycloid/contact/contact_parameters.h>
#include <cycloid/dynamics/transient_parameters.h>
#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/geometry/deviations.h>
#include <cycloid/mesh/mesh_parameters.h>
#include <cycloid/mesh/stage_mesh.h>
#include <cycloid/parameters/loading.h>
#include <cycloid/parameters/material.h>
#include <cycloid/parameters/run.h>
#include <cycloid/parameters/scene.h>
#include <cycloid/profile/profile_parameters.h>
#include <cycloid/reduced/reduced_parameters.h>
#include <cycloid/support/crank_bearing_parameters.h>
#include <cycloid/tolerance/tolerance_parameters.h>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace cycloid
{
  namespace app
  {
    /**
     * @brief Every parameter of a run, grouped by subsection; each group
     * declares and parses its own subsection. Only the app layer sees the
     * whole set: it hands each subsystem the typed settings it needs
     * (model_settings(), mesh_settings(), and the run settings built in
     * app/run.cc), so no subsystem depends on the parameters of another.
     */
    struct AllParameters
    {
      parameters::RunParameters run; ///< Top level: `Run`, `Output directory`.
      geometry::GeometryParameters   geometry; ///< Subsection `Geometry`.
      parameters::MaterialParameters material; ///< Subsection `Material`.
      parameters::LoadingParameters  loading;  ///< Subsection `Loading`.
      parameters::SceneParameters    scene;    ///< Subsection `Scene`.
      analytic::AnalyticParameters   analytic; ///< Subsection `Analytic`.
      mesh::MeshParameters           mesh;     ///< Subsection `Mesh`.
      contact::ContactParameters
        contact; ///< Subsections `Contact` and `Solver`.
      /** Subsection Transient. */
      dynamics::TransientParameters transient;
      /** Subsection Profile (Run = profile). */
      profile::ProfileParameters profile;
      /** Subsection Reduced (Run = reduced). */
      reduced::ReducedParameters reduced;
      /** Subsection Crank bearings. */
      support::CrankBearingParameters bearings;
      /** Subsection Tolerance study (Run = tolerance). */
      tolerance::ToleranceParameters tolerance;
      /** Subsection Deviations: read into `geometry` by read(). */
      geometry::DeviationsParameters deviations;

      /**
       * Every entry with the value this run uses, as a parameter file
       * (deal.II's short PRM format): read() fills it and the run writes it
       * to its output directory as `parameters.prm`, so that running on
       * that file repeats the run. Empty if the set was not made by read().
       */
      std::string parameter_file;

      /**
       * The same values as deal.II's JSON (every entry with its value,
       * default, documentation and pattern): written beside
       * `parameters.prm` as `parameters.json`, so that scripts read a
       * run's parameters as deal.II read them instead of parsing the prm
       * grammar themselves. Empty if the set was not made by read().
       */
      std::string parameter_json;

      /**
       * The entries the parameter file sets, as "Subsection/Entry" (or
       * "Entry" at the top level) with their values as written: read()
       * fills it, so that a run can name
       * the entries its mode ignores (app/ignored_entries.h) and an error
       * about a value left at its default can say so. Empty if the set was
       * not made by read().
       */
      std::map<std::string, std::string> set_in_file;

      /** The entries of set_in_file whose value equals the declared
       * default (a written parameters.prm sets every entry): setting an
       * ignored entry to its default changes nothing, so no warning names
       * it. */
      std::set<std::string> set_to_default;

      /** What the parameters resolved on their own, for the run's first
       * console lines ("2D FE: one disc (Scene/Number of discs = auto)"). */
      std::vector<std::string> notes;

      /** Declare every subsection. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse every subsection from an already read handler, and resolve
       * the `auto` entries that depend on the run mode (notes). */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /** Resolve `Mesh/Error estimate` (and first `Mesh/Target accuracy`)
       * for the run mode and dimension: on (raising Contact refinements to
       * the levels the estimate coarsens) or off. Adds a note for the user
       * where the result is not what the file says. */
      void
      resolve_error_estimate();

      /** Throw if `Crank bearings` cannot be run: needle bearings in a
       * mode whose model does not have them yet, fewer than two crank
       * holes, or rollers that do not fit the hole. */
      void
      check_bearings() const;

      /** Resolve `Mesh/Target accuracy = auto`: the Warning threshold if
       * the run @p solves FE states in 2D with the estimate not off, else
       * 0 (with a note when it is set). */
      void
      resolve_target_accuracy(bool solves);

      /** Resolve `Mesh/Bulk error estimate = auto` once the estimate is
       * on: on in 2D, off in 3D (with a note if the run @p solves FE
       * states). */
      void
      resolve_bulk_error(bool solves);

      /**
       * Read the deviations files (relative paths from @p directory) into
       * `geometry`, refuse them in a run mode that does not honour them
       * yet, and check that no deviated pin overlaps a disc at rest at the
       * run's crank angles.
       */
      void
      read_deviations(const std::string &directory);

      /**
       * Declare, read @p filename (with a clear error if it does not exist
       * or does not parse: a misspelled name gets the closest declared
       * ones, see parse_input_explained()) and parse.
       */
      static AllParameters
      read(const std::string &filename);

      /** The settings of the analytical model. */
      analytic::ModelSettings
      model_settings() const
      {
        return {geometry, material, scene, analytic, bearings};
      }

      /** Throw if the file sets both Geometry/Pin circle radius and a
       * Shortening coefficient that disagrees with it (@p set_in_file: the
       * entries the file sets, as read; @p prm parsed). */
      static void
      check_pin_circle(dealii::ParameterHandler                 &prm,
                       const std::map<std::string, std::string> &set_in_file);

      /** The settings of the mesh. */
      mesh::MeshSettings
      mesh_settings() const
      {
        return {geometry, scene, mesh};
      }
    };

    /**
     * The entries that the parameter file @p filename sets, as
     * "Subsection/Entry" ("Entry" at the top level, "A/B/Entry" in a
     * nested subsection), each with its value as deal.II read it (the last
     * one if the file sets an entry twice): the file parsed against every
     * declaration with record_entries_set(). AllParameters::read() records
     * the same while it parses.
     */
    std::map<std::string, std::string>
    entries_set_in(const std::string &filename);
  } // namespace app
} // namespace cycloid

#endif

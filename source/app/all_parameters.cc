#include <deal.II/base/exceptions.h>

#include <deal.II/base/utilities.h>

#include <cycloid/app/all_parameters.h>
#include <cycloid/app/parameter_suggestions.h>
#include <cycloid/parameters/or_auto.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace cycloid
{
  namespace app
  {
    namespace
    {
      /** The value of entry @p path ("A/B/Entry") in @p prm. */
      std::string
      value_of(dealii::ParameterHandler &prm, const std::string &path)
      {
        const auto parts = dealii::Utilities::split_string_list(path, '/');
        for (std::size_t i = 0; i + 1 < parts.size(); ++i)
          prm.enter_subsection(parts[i]);
        const std::string value = prm.get(parts.back());
        for (std::size_t i = 0; i + 1 < parts.size(); ++i)
          prm.leave_subsection();
        return value;
      }
    } // namespace



    void
    AllParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      parameters::RunParameters::declare_parameters(prm);
      geometry::GeometryParameters::declare_parameters(prm);
      parameters::MaterialParameters::declare_parameters(prm);
      parameters::LoadingParameters::declare_parameters(prm);
      parameters::SceneParameters::declare_parameters(prm);
      analytic::AnalyticParameters::declare_parameters(prm);
      mesh::MeshParameters::declare_parameters(prm);
      contact::ContactParameters::declare_parameters(prm);
      dynamics::TransientParameters::declare_parameters(prm);
      profile::ProfileParameters::declare_parameters(prm);
      reduced::ReducedParameters::declare_parameters(prm);
      tolerance::ToleranceParameters::declare_parameters(prm);
      support::CrankBearingParameters::declare_parameters(prm);
      geometry::DeviationsParameters::declare_parameters(prm);
    }



    void
    AllParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      run.parse_parameters(prm);
      geometry.parse_parameters(prm);
      material.parse_parameters(prm);
      loading.parse_parameters(prm);
      scene.parse_parameters(prm);
      analytic.parse_parameters(prm);
      mesh.parse_parameters(prm);
      contact.parse_parameters(prm);
      transient.parse_parameters(prm);
      profile.parse_parameters(prm);
      reduced.parse_parameters(prm);
      tolerance.parse_parameters(prm);
      bearings.parse_parameters(prm);
      deviations.parse_parameters(prm);
      // Where the run mode and the dimension are both known.
      notes.clear();
      const std::string discs = scene.resolve_number_of_discs(run.fe());
      if (!discs.empty())
        notes.push_back(discs);
      resolve_error_estimate();
      check_bearings();
      AssertThrow(scene.pin_core_radius < geometry.pin_radius,
                  dealii::ExcMessage(
                    "Scene/Pin core radius (" +
                    dealii::Utilities::to_string(scene.pin_core_radius) +
                    " mm) must be smaller than Geometry/Pin radius (" +
                    dealii::Utilities::to_string(geometry.pin_radius) +
                    " mm)."));
    }



    void
    AllParameters::check_bearings() const
    {
      using M = parameters::RunParameters::Mode;
      if (!bearings.needle())
        return;
      AssertThrow(run.mode == M::analytic || run.mode == M::reduced ||
                    run.mode == M::tolerance || run.mode == M::profile ||
                    run.mode == M::mesh,
                  dealii::ExcMessage(
                    "Crank bearings/Model = needle: the full FE model "
                    "(Run = quasi-static, phase-sweep, transient) does not "
                    "have crank bearings yet; Run = analytic, reduced or "
                    "tolerance solves them (doc/bearings.md)."));
      AssertThrow(geometry.n_crank_holes >= 2,
                  dealii::ExcMessage(
                    "Crank bearings/Model = needle needs Geometry/Number of "
                    "crank holes >= 2 (a disc on one bearing is free to "
                    "turn about it)."));
      AssertThrow(scene.load_introduction ==
                    parameters::SceneParameters::LoadIntroduction::crank_holes,
                  dealii::ExcMessage(
                    "Crank bearings/Model = needle needs Scene/Load "
                    "introduction = crank holes: the bearings sit in the "
                    "crank holes, and the disc's compliance is taken with "
                    "them held (with Load introduction = bore it would be "
                    "held at the bore)."));
      // The sizes fit the hole (throws with the reason otherwise).
      bearings.size(geometry.crank_hole_radius, geometry.tooth_width);
    }



    void
    AllParameters::resolve_error_estimate()
    {
      using M      = parameters::RunParameters::Mode;
      auto      &e = mesh.error;
      const bool solves =
        run.mode == M::quasi_static || run.mode == M::phase_sweep;
      const bool fe = solves || run.mode == M::mesh;
      resolve_target_accuracy(solves);
      if (!fe || !e.estimates(scene.dimension))
        {
          // Transient runs keep one mesh; the reduced model's coarse scene
          // is no answer to estimate; 3D with auto and no target.
          if (solves && e.mode == mesh::ErrorControl::Mode::automatic)
            notes.push_back(
              "Mesh/Error estimate = auto: off in 3D, so the states carry no "
              "error estimate from nested levels (they cost nearly as much "
              "as the state; Error estimate = true or a Target accuracy "
              "turns it on); the mesh warning then rests on the contact "
              "resolution, nodes across the Hertz width of the most loaded "
              "pin (stiffness.csv hertz_nodes, resolution_error)");
          e.mode = mesh::ErrorControl::Mode::off;
          e.bulk = false;
          return;
        }
      e.mode = mesh::ErrorControl::Mode::on;
      resolve_bulk_error(solves);
      const unsigned int needed = mesh::ErrorControl::coarser_levels;
      if (mesh.contact_refinements >= needed)
        return;
      const unsigned int asked = mesh.contact_refinements;
      mesh.contact_refinements = needed;
      notes.push_back(
        "Mesh/Error estimate: Contact refinements raised from " +
        std::to_string(asked) + " to " + std::to_string(needed) +
        " (the estimate solves each state also with its finest contact "
        "level coarsened once and twice; Error estimate = false keeps " +
        std::to_string(asked) + ")");
    }



    void
    AllParameters::resolve_bulk_error(const bool solves)
    {
      auto &e = mesh.error;
      if (!e.automatic_bulk)
        return;
      e.bulk = scene.dimension == 2;
      if (solves && !e.bulk)
        notes.push_back(
          "Mesh/Bulk error estimate = auto: off in 3D, so the error "
          "estimates leave out the bulk mesh's error (the cells below the "
          "two finest levels; its extra solve has several times the "
          "state's DoFs in 3D; Bulk error estimate = true adds it)");
    }



    void
    AllParameters::resolve_target_accuracy(const bool solves)
    {
      auto &e = mesh.error;
      if (!e.automatic_target)
        return;
      // 3D: every cycle costs minutes and the estimate itself nearly a
      // state; other modes solve no state or keep one mesh.
      if (!solves || scene.dimension != 2 ||
          e.mode == mesh::ErrorControl::Mode::off)
        return;
      if (e.warning_threshold <= 0)
        {
          // A threshold of 0 turns the warning off, and with it the
          // target it stands for: say so rather than promise refinement.
          notes.push_back(
            "Mesh/Target accuracy = auto: 0 (off), because Warning "
            "threshold = 0 turns the warning off; the states keep the mesh "
            "asked for (set Target accuracy to a number to refine)");
          return;
        }
      e.target_accuracy = e.warning_threshold;
      std::ostringstream note;
      note << "Mesh/Target accuracy = auto: " << e.target_accuracy
           << " (the Warning threshold): each state refines at its active "
              "contacts, at most "
           << e.max_cycles
           << " cycles, until its error estimates are below it (Target "
              "accuracy = 0 keeps the mesh asked for)";
      notes.push_back(note.str());
    }



    void
    AllParameters::check_pin_circle(
      dealii::ParameterHandler                 &prm,
      const std::map<std::string, std::string> &set_in_file)
    {
      const auto rp = set_in_file.find("Geometry/Pin circle radius");
      const auto k1 = set_in_file.find("Geometry/Shortening coefficient");
      if (rp == set_in_file.end() || k1 == set_in_file.end() ||
          parameters::is_auto(rp->second))
        return;
      prm.enter_subsection("Geometry");
      const double ezp =
        prm.get_double("Eccentricity") * prm.get_integer("Number of pins");
      prm.leave_subsection();
      const double given = dealii::Utilities::string_to_double(k1->second);
      const double from_rp =
        ezp / dealii::Utilities::string_to_double(rp->second);
      AssertThrow(std::abs(given - from_rp) <= 1e-9 * from_rp,
                  dealii::ExcMessage(
                    "Geometry/Pin circle radius = " + rp->second +
                    " mm and Geometry/Shortening coefficient = " + k1->second +
                    " disagree: rp = e zp / K1 gives K1 = " +
                    dealii::Utilities::to_string(from_rp) +
                    " for this rp. Set one of the two (the other follows)."));
    }



    void
    AllParameters::read_deviations(const std::string &directory)
    {
      if (!deviations.any())
        return;
      deviations.read_into(geometry, directory);
      const geometry::CycloidGeometry geo(geometry);
      geometry::check_rest_overlap(geo,
                                   loading.crank_angles(geo.mesh_period()),
                                   scene.n_discs,
                                   deviations,
                                   directory);
    }



    AllParameters
    AllParameters::read(const std::string &filename)
    {
      {
        std::ifstream in(filename);
        AssertThrow(in.good(),
                    dealii::ExcMessage("cannot open the parameter file '" +
                                       filename + "'."));
      }
      dealii::ParameterHandler prm;
      declare_parameters(prm);
      AllParameters result;
      record_entries_set(prm, result.set_in_file);
      parse_input_explained(prm, filename);
      // The file's own values, before parse_parameters() derives K1 from
      // a given rp (and writes it back for parameters.prm).
      check_pin_circle(prm, result.set_in_file);
      result.parse_parameters(prm);
      const std::string directory =
        std::filesystem::path(filename).parent_path().string();
      result.read_deviations(directory);
      // The files as absolute paths, so that parameters.prm repeats the run
      // from its own directory.
      prm.enter_subsection("Deviations");
      for (const auto &[entry, file] :
           {std::make_pair("Pin deviations file", result.deviations.pin_file),
            std::make_pair("Disc deviations file",
                           result.deviations.disc_file)})
        if (!file.empty())
          prm.set(entry,
                  std::filesystem::absolute(
                    geometry::DeviationsParameters::resolve(file, directory))
                    .string());
      prm.leave_subsection();
      dealii::ParameterHandler defaults;
      declare_parameters(defaults);
      for (const auto &entry : result.set_in_file)
        if (value_of(prm, entry.first) == value_of(defaults, entry.first))
          result.set_to_default.insert(entry.first);
      result.geometry.set_in_file.emplace();
      for (const auto &entry : result.set_in_file)
        if (entry.first.rfind("Geometry/", 0) == 0)
          result.geometry.set_in_file->insert(entry.first.substr(9));

      // Every entry, not only those the file sets: a default that changes
      // in a later version does not change what the written file repeats.
      std::ostringstream text;
      text << "# The parameters of a cycloid-contact run, read from '"
           << filename
           << "': every entry with the value the run used.\n"
              "# 'cycloid-contact parameters.prm' repeats the run (into "
              "the Output directory below,\n# relative to where it is "
              "started).\n";
      prm.print_parameters(text,
                           dealii::ParameterHandler::ShortPRM |
                             dealii::ParameterHandler::KeepDeclarationOrder);
      result.parameter_file = text.str();
      std::ostringstream json;
      prm.print_parameters(json,
                           dealii::ParameterHandler::JSON |
                             dealii::ParameterHandler::KeepDeclarationOrder);
      result.parameter_json = json.str();
      return result;
    }



    std::map<std::string, std::string>
    entries_set_in(const std::string &filename)
    {
      dealii::ParameterHandler prm;
      AllParameters::declare_parameters(prm);
      std::map<std::string, std::string> set;
      record_entries_set(prm, set);
      parse_input_explained(prm, filename);
      return set;
    }
  } // namespace app
} // namespace cycloid

#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>

#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <cycloid/mesh/contact_refinement.h>
#include <cycloid/stage/cost_estimate.h>
#include <cycloid/stage/error_control_loop.h>

#include <cctype>
#include <iomanip>
#include <sstream>

namespace cycloid
{
  namespace stage
  {
    namespace
    {
      /** @p text on one line, whitespace runs as one blank. */
      std::string
      trimmed(const std::string &text)
      {
        std::string out;
        for (const char c : text)
          if (!std::isspace(static_cast<unsigned char>(c)))
            out += c;
          else if (!out.empty() && out.back() != ' ')
            out += ' ';
        while (!out.empty() && out.back() == ' ')
          out.pop_back();
        return out;
      }



      /** The ids that @p id_of gives for the locally owned active cells of
       * @p tria (an empty optional: none), from every rank. Cells refined
       * or coarsened now are refined or coarsened back later, and on a
       * distributed mesh a cell may move to another rank with the new
       * partition in between: so every rank gets all of them. */
      template <int dim, typename IdOf>
      std::set<dealii::CellId>
      gather_cell_ids(const MPI_Comm                    comm,
                      const dealii::Triangulation<dim> &tria,
                      const IdOf                       &id_of)
      {
        std::vector<dealii::CellId::binary_type> mine;
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned())
            if (const std::optional<dealii::CellId> id = id_of(cell))
              mine.push_back(id->template to_binary<dim>());
        std::set<dealii::CellId> all;
        for (const auto &part : dealii::Utilities::MPI::all_gather(comm, mine))
          for (const auto &id : part)
            all.insert(dealii::CellId(id));
        return all;
      }
    } // namespace



    void
    SolveCost::add(const results::StageState &level)
    {
      iterations += level.iterations;
      linear += level.linear_iterations;
      setups += level.preconditioner_setups;
    }



    template <int dim>
    ErrorControlLoop<dim>::ErrorControlLoop(
      StageScene<dim>                  &scene,
      const mesh::MeshParameters       &mesh,
      const dealii::ConditionalOStream &pcout)
      : scene(scene)
      , mesh(mesh)
      , pcout(pcout)
      , tria(scene.triangulation())
      , comm(scene.triangulation().get_communicator())
    {}



    template <int dim>
    ControlledState
    ErrorControlLoop<dim>::solve(const double load)
    {
      std::vector<results::StageState> levels; // coarsest first
      const bool                       have_coarse =
        mesh.error.estimates(dim) && solve_coarser_levels(load, levels);
      results::StageState fine = solve_level(load);
      if (have_coarse)
        results::set_error_estimate(levels[0],
                                    levels[1],
                                    fine,
                                    scene.contact_level());
      std::optional<results::BulkError> bulk;
      if (have_coarse && mesh.error.bulk)
        bulk = measure_bulk_error(load, fine);
      // The target's cycles aim at the sum, with the part measured on the
      // first mesh: refining at the contacts leaves most of the bulk as
      // it is.
      if (bulk)
        results::add_bulk_error(*bulk, fine);
      unsigned int cycle = 0;
      for (; refine_again(cycle, have_coarse, fine); ++cycle)
        {
          if (!refine_at_contacts())
            break;
          if (have_coarse)
            levels = {std::move(levels[1]), std::move(fine)};
          fine = solve_level(load);
          if (have_coarse)
            results::set_error_estimate(levels[0],
                                        levels[1],
                                        fine,
                                        scene.contact_level());
          if (bulk)
            results::add_bulk_error(*bulk, fine);
        }
      if (bulk && cycle > 0)
        remeasure_bulk_error(load, levels, fine);
      if (!out.level_failure.empty() && !fine.error.available())
        fine.error.failure = out.level_failure;
      report_accuracy(fine);
      out.state = std::move(fine);
      return out;
    }



    template <int dim>
    results::StageState
    ErrorControlLoop<dim>::solve_level(const double load)
    {
      results::StageState s = scene.solve_level(load);
      out.cost.add(s);
      return s;
    }



    template <int dim>
    bool
    ErrorControlLoop<dim>::solve_coarser_levels(
      const double                      load,
      std::vector<results::StageState> &coarser)
    {
      const unsigned int n = mesh::ErrorControl::coarser_levels;
      if (tria.n_global_levels() - 1 < mesh.global_refinements + n)
        return false;
      const auto n_cells  = tria.n_global_active_cells();
      const auto original = scene.contact_problem().active_set_snapshot();
      std::vector<std::set<dealii::CellId>> parents;
      {
        dealii::TimerOutput::Scope t(scene.timer(), "error estimate: coarsen");
        for (unsigned int k = 0; k < n; ++k)
          parents.push_back(coarsen_finest_level());
        scene.rebuild(original);
      }
      // Coarsest first, each level warm-started from the one below. A
      // level that fails (an active set that cycles on a coarse flank, a
      // solver that does not converge) leaves the state without an
      // estimate, not without a result: the mesh asked for is restored and
      // solved from the warm start it had.
      auto snapshot = original;
      bool solved   = true;
      for (unsigned int k = n; k-- > 0;)
        {
          try
            {
              coarser.push_back(solve_level(load));
              snapshot = scene.contact_problem().active_set_snapshot();
            }
          catch (const dealii::ExceptionBase &e)
            {
              std::ostringstream message;
              e.print_info(message);
              out.level_failure = trimmed(message.str());
              solved            = false;
            }
          catch (const std::exception &e)
            {
              out.level_failure = trimmed(e.what());
              solved            = false;
            }
          dealii::TimerOutput::Scope t(scene.timer(),
                                       "error estimate: coarsen");
          if (!solved)
            {
              for (unsigned int j = k + 1; j-- > 0;)
                refine_cells(parents[j]);
              scene.rebuild(original);
              break;
            }
          refine_cells(parents[k]);
          scene.rebuild(snapshot);
        }
      AssertThrow(tria.n_global_active_cells() == n_cells,
                  dealii::ExcMessage("the error estimate's coarser levels did "
                                     "not refine back to the mesh asked for."));
      return solved;
    }



    template <int dim>
    bool
    ErrorControlLoop<dim>::solve_bulk_level(const double         load,
                                            results::StageState &bulk)
    {
      const auto n_cells  = tria.n_global_active_cells();
      const auto original = scene.contact_problem().active_set_snapshot();
      // The contact levels' estimate coarsens the finest levels and so
      // sees the error of the cells on them; every other cell is the same
      // on all its levels. Those are refined: the cells at the global
      // refinement level and the graded halo of levels between it and
      // the contacts (that halo alone put pin forces 1-3 % off with an
      // estimate of 0.3-0.5 %, against Q2: doc/error-estimate.md §5).
      const unsigned int       top  = tria.n_global_levels() - 1;
      const unsigned int       seen = mesh::ErrorControl::coarser_levels;
      std::set<dealii::CellId> refined;
      {
        dealii::TimerOutput::Scope t(scene.timer(),
                                     "error estimate: bulk refine");
        for (const auto &cell : tria.active_cell_iterators())
          if (!cell->is_artificial() &&
              static_cast<unsigned int>(cell->level()) + seen <= top)
            cell->set_refine_flag();
        tria.prepare_coarsening_and_refinement();
        if (!refinement_fits("the bulk level's refinement"))
          {
            for (const auto &cell : tria.active_cell_iterators())
              cell->clear_refine_flag();
            return false;
          }
        refined = gather_cell_ids(comm, tria, [](const auto &cell) {
          return cell->refine_flag_set() ?
                   std::optional<dealii::CellId>(cell->id()) :
                   std::nullopt;
        });
        tria.execute_coarsening_and_refinement();
        scene.rebuild(original);
      }
      bool solved = true;
      try
        {
          bulk = solve_level(load);
        }
      catch (const std::exception &e)
        {
          out.level_failure = trimmed(e.what());
          solved            = false;
        }
      dealii::TimerOutput::Scope t(scene.timer(),
                                   "error estimate: bulk refine");
      // Back to the mesh asked for: coarsen the children of the cells
      // refined above.
      for (const auto &cell : tria.active_cell_iterators())
        if (!cell->is_artificial() && cell->level() > 0 &&
            refined.count(cell->parent()->id()) > 0)
          cell->set_coarsen_flag();
      tria.execute_coarsening_and_refinement();
      scene.rebuild(original);
      AssertThrow(tria.n_global_active_cells() == n_cells,
                  dealii::ExcMessage("the error estimate's bulk level did "
                                     "not coarsen back to the mesh asked "
                                     "for."));
      return solved;
    }



    template <int dim>
    std::optional<results::BulkError>
    ErrorControlLoop<dim>::measure_bulk_error(const double               load,
                                              const results::StageState &fine)
    {
      results::StageState refined;
      if (solve_bulk_level(load, refined))
        return results::bulk_error(refined, fine);
      pcout << "  no bulk error estimate: "
            << (out.memory_stop.empty() ? out.level_failure : out.memory_stop)
            << std::endl;
      // Neither is about the contact levels reported later.
      out.memory_stop.clear();
      out.level_failure.clear();
      return std::nullopt;
    }



    template <int dim>
    void
    ErrorControlLoop<dim>::remeasure_bulk_error(
      const double                            load,
      const std::vector<results::StageState> &levels,
      results::StageState                    &fine)
    {
      // The cycles added a graded halo around the contacts, finer than the
      // first mesh there but not seen by the contact levels: the part the
      // state reports is its own mesh's. If that level does not fit, the
      // first mesh's part stays (measure_bulk_error() says so), and what
      // stopped the cycles is still reported.
      const std::string stop    = out.memory_stop;
      const std::string failure = out.level_failure;
      const auto        bulk    = measure_bulk_error(load, fine);
      out.memory_stop           = stop;
      out.level_failure         = failure;
      if (!bulk)
        return;
      results::set_error_estimate(levels[0],
                                  levels[1],
                                  fine,
                                  scene.contact_level());
      results::add_bulk_error(*bulk, fine);
    }



    template <int dim>
    bool
    ErrorControlLoop<dim>::refine_again(const unsigned int         cycle,
                                        const bool                 have_coarse,
                                        const results::StageState &fine) const
    {
      const auto &m = mesh;
      if (cycle < m.adaptive_cycles)
        return true;
      return m.error.target_accuracy > 0 && have_coarse &&
             fine.error.largest() > m.error.target_accuracy &&
             cycle < m.adaptive_cycles + m.error.max_cycles;
    }



    template <int dim>
    bool
    ErrorControlLoop<dim>::refine_at_contacts()
    {
      dealii::TimerOutput::Scope t(scene.timer(), "refine at contacts");
      // Cells of any body next to an active node, up to the level cap.
      const unsigned int              cap = level_cap();
      std::vector<dealii::Point<dim>> points;
      for (const unsigned int i : scene.contact_problem().active_set())
        points.push_back(scene.contact_problem().slave_nodes()[i].position);
      unsigned int flagged = 0;
      for (const auto &cell : tria.active_cell_iterators())
        {
          if (cell->is_artificial() ||
              static_cast<unsigned int>(cell->level()) >= cap)
            continue;
          for (const auto &p : points)
            if (mesh::near_contact_node<dim>(cell, p))
              {
                cell->set_refine_flag();
                ++flagged;
                break;
              }
        }
      // Collective: on a distributed mesh a rank may hold no cell near an
      // active node while the others refine.
      if (dealii::Utilities::MPI::sum(flagged, comm) == 0)
        return false;
      tria.prepare_coarsening_and_refinement();
      if (!refinement_fits())
        {
          for (const auto &cell : tria.active_cell_iterators())
            cell->clear_refine_flag();
          return false;
        }
      const auto snapshot = scene.contact_problem().active_set_snapshot();
      tria.execute_coarsening_and_refinement();
      scene.rebuild(snapshot);
      return true;
    }



    template <int dim>
    bool
    ErrorControlLoop<dim>::refinement_fits(const std::string &what)
    {
      // Each cell counted by its owner (a shared mesh has the same flags
      // on every rank, a distributed one on the owner's cells).
      std::size_t flagged = 0;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned() && cell->refine_flag_set())
          ++flagged;
      flagged            = dealii::Utilities::MPI::sum(flagged, comm);
      const double cells = tria.n_global_active_cells();
      const double grown = (cells + ((1u << dim) - 1) * flagged) / cells;
      const auto   dofs  = static_cast<dealii::types::global_dof_index>(
        grown * scene.contact_problem().elasticity().n_dofs());
      const double needed    = scene.memory_needed(dofs);
      const double available = available_memory_bytes(comm);
      if (needed <= available)
        return true;
      std::ostringstream why;
      why << std::setprecision(3) << what << " (" << flagged << " cells, about "
          << dofs << " DoFs) would need an estimated " << needed / 1e9
          << " GB, more than the " << available / 1e9
          << " GB available (MemAvailable and what the run holds)";
      out.memory_stop = why.str();
      pcout << "  refinement stopped: " << out.memory_stop
            << "; the state keeps the mesh it was solved on" << std::endl;
      return false;
    }



    template <int dim>
    std::set<dealii::CellId>
    ErrorControlLoop<dim>::coarsen_finest_level()
    {
      // The finest cells all lie at the contacts (only the contact
      // refinements reach that level); their parents are remembered, so
      // that refining those again restores the mesh exactly.
      const unsigned int top = tria.n_global_levels() - 1;
      for (const auto &cell : tria.active_cell_iterators())
        if (!cell->is_artificial() &&
            static_cast<unsigned int>(cell->level()) == top)
          cell->set_coarsen_flag();
      tria.prepare_coarsening_and_refinement();
      const auto parents = gather_cell_ids(comm, tria, [](const auto &cell) {
        return cell->coarsen_flag_set() ?
                 std::optional<dealii::CellId>(cell->parent()->id()) :
                 std::nullopt;
      });
      tria.execute_coarsening_and_refinement();
      return parents;
    }



    template <int dim>
    void
    ErrorControlLoop<dim>::refine_cells(const std::set<dealii::CellId> &cells)
    {
      for (const auto &cell : tria.active_cell_iterators())
        if (!cell->is_artificial() && cells.count(cell->id()) > 0)
          cell->set_refine_flag();
      tria.execute_coarsening_and_refinement();
    }



    template <int dim>
    unsigned int
    ErrorControlLoop<dim>::level_cap() const
    {
      // The a-priori refinements, the adaptive cycles, and what the target
      // accuracy may add.
      const auto  &m     = mesh;
      unsigned int extra = 0;
      if (m.error.target_accuracy > 0)
        extra += m.error.max_cycles;
      return m.global_refinements + m.contact_refinements + m.adaptive_cycles +
             extra;
    }



    template <int dim>
    void
    ErrorControlLoop<dim>::report_accuracy(const results::StageState &s) const
    {
      const double target = mesh.error.target_accuracy;
      if (target == 0 || !s.error.available())
        return;
      pcout << "  target accuracy " << target << ": "
            << (s.error.largest() <= target ? "reached" : "NOT reached")
            << " at contact level " << s.error.contact_level << " (" << s.dofs
            << " DoFs), largest estimate " << s.error.largest()
            << (s.error.largest() <= target ?
                  std::string() :
                !out.memory_stop.empty() ?
                  "; " + out.memory_stop :
                  "; Mesh/Maximum accuracy cycles (now " +
                    std::to_string(mesh.error.max_cycles) +
                    ") or Mesh/Contact refinements would "
                    "go further")
            << std::endl;
      if (s.error.largest() > target && s.error.bulk > 0.5 * target)
        pcout << "  the bulk mesh's part of the estimate is " << s.error.bulk
              << ": the target's cycles refine at the "
              << "contacts and do not reduce it; " << results::bulk_advice
              << std::endl;
    }



    template class ErrorControlLoop<2>;
    template class ErrorControlLoop<3>;
  } // namespace stage
} // namespace cycloid

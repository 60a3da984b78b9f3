#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/cell_id.h>
#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <cycloid/analytic/pair_stiffness.h>
#include <cycloid/elasticity/heap.h>
#include <cycloid/elasticity/support_points.h>
#include <cycloid/mesh/contact_refinement.h>
#include <cycloid/postprocess/report.h>
#include <cycloid/results/error_estimate.h>
#include <cycloid/stage/cost_estimate.h>
#include <cycloid/stage/stage_scene.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <set>
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
    } // namespace



    namespace ids = mesh::ids;
    namespace u   = results::units;
    using Scene   = parameters::SceneParameters;

    namespace
    {
      /** Component @p comp of the unit rigid rotation about @p centre at
       * @p x: e_z x (x - c) = (-(y - cy), x - cx, 0). */
      template <int dim>
      double
      unit_rotation(const dealii::Point<2>   &centre,
                    const dealii::Point<dim> &x,
                    const unsigned int        comp)
      {
        return comp == 0 ? -(x[1] - centre[1]) :
               comp == 1 ? x[0] - centre[0] :
                           0.;
      }

      /** The angle of @p x about @p centre in the xy plane, measured from
       * the direction @p from [rad], in [-pi, pi]. */
      template <int dim>
      double
      angle_about(const dealii::Point<dim> &x,
                  const dealii::Point<2>   &centre,
                  const double              from)
      {
        return std::remainder(std::atan2(x[1] - centre[1], x[0] - centre[0]) -
                                from,
                              2. * u::pi);
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



    analytic::ModelSettings
    StageSettings::model_settings() const
    {
      return {geometry, material, scene, analytic};
    }



    mesh::MeshSettings
    StageSettings::mesh_settings() const
    {
      return {geometry, scene, mesh};
    }



    std::string
    description(const StageSettings &settings)
    {
      std::ostringstream s;
      s << settings.scene.dimension << "D, " << settings.scene.n_discs
        << " disc(s), "
        << (settings.scene.pins == Scene::PinModel::rigid ? "rigid" : "elastic")
        << " pins";
      return s.str();
    }



    template <int dim>
    StageScene<dim>::StageScene(const StageSettings     &settings,
                                const mesh::MeshRequest &request,
                                const MPI_Comm           comm)
      : settings(settings)
      , comm(comm)
      , geo(settings.geometry)
      , model(settings.model_settings())
      , psi_mesh(request.crank_angle)
      , psi(request.crank_angle)
      , pcout(std::cout,
              !settings.quiet &&
                dealii::Utilities::MPI::this_mpi_process(comm) == 0)
      // Rank 0's own times, on MPI_COMM_SELF: a timer on the run's
      // communicator synchronises the ranks when a section starts and ends
      // (three reductions per section), also while an exception unwinds
      // through a TimerOutput::Scope on one rank only, where those
      // reductions would meet the other ranks' unrelated collectives. And
      // its destructor, during any unwinding, prints a "TimerOutput objects
      // finalize timed values ... uncaught exception" notice instead of the
      // error (deal.II 9.4, source/base/timer.cc). On MPI_COMM_SELF neither
      // happens; the summary is the same table of rank 0's wall times.
      , timing(MPI_COMM_SELF,
               pcout,
               dealii::TimerOutput::never,
               dealii::TimerOutput::wall_times)
      , tria(mesh::create_triangulation<dim>(settings.mesh, comm))
    {
      AssertThrow(settings.scene.load_introduction !=
                      Scene::LoadIntroduction::crank_holes ||
                    settings.geometry.n_crank_holes > 0,
                  dealii::ExcMessage(
                    "Scene/Load introduction = crank holes needs "
                    "Geometry/Number of crank holes > 0 (the disc would have "
                    "no load surface); use Load introduction = bore."));
      pin_model = contact::create_pin_model<dim>(
        {settings.geometry, settings.material, settings.scene});
      make_grid(request);
      setup_contact();
      setup_system();
      announce_cost();
      compute_rotation_field();
    }



    template <int dim>
    void
    StageScene<dim>::make_grid(const mesh::MeshRequest &request)
    {
      dealii::TimerOutput::Scope t(timing, "make grid");
      mesh::create_stage_mesh(settings.mesh_settings(), request, *tria);
      pcout << "  mesh: " << dim << "D, " << settings.scene.n_discs
            << " disc(s), " << tria->n_global_active_cells() << " cells";
      if (settings.mesh.distributed)
        {
          // What each rank holds: its own cells, a ghost layer and the
          // coarse grid (artificial where another rank refined it).
          const auto held = dealii::Utilities::MPI::min_max_avg(
            static_cast<double>(tria->n_active_cells()), comm);
          pcout << ", distributed (p4est): " << held.min << " to " << held.max
                << " active cells held a rank";
        }
      pcout << std::endl;
    }



    template <int dim>
    void
    StageScene<dim>::setup_contact()
    {
      std::map<dealii::types::material_id, parameters::ElasticMaterial>
        materials;
      for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
        materials[ids::disc(d)] = settings.material.disc;
      pin_model->add_materials(materials);

      const auto              &c = settings.contact;
      contact::ContactSettings cs;
      cs.max_iterations       = c.max_active_set_iterations;
      cs.search_distance      = c.search_distance;
      cs.solver_tolerance     = c.solver_tolerance;
      cs.inner_tolerance      = c.inner(dim);
      cs.reuse_preconditioner = c.reuse_preconditioner;
      cs.residual_tolerance   = c.residual_tolerance;
      cs.formulation          = c.formulation;
      cs.solver               = c.linear_solver;
      cs.amg_hierarchy        = c.hierarchy(dim);
      // The Schur path takes its rows from the hanging and support lines
      // of the cells a rank holds: on a distributed mesh they differ
      // between the ranks, so it runs on the shared mesh only.
      const bool schur_asked =
        c.linear_solver == elasticity::LinearSolver::direct &&
        c.schur_complement.value_or(false);
      AssertThrow(!settings.mesh.distributed || !schur_asked,
                  dealii::ExcMessage(
                    "Solver/Contact Schur complement = true needs "
                    "Mesh/Triangulation = shared; on a distributed mesh set "
                    "it to auto or false (the direct solver then factorises "
                    "each active set)."));
      cs.schur_complement = c.use_schur_complement(settings.one_operator) &&
                            !settings.mesh.distributed;
      cs.schur_columns = c.schur_columns;
      contact          = std::make_unique<contact::ContactProblem<dim>>(
        *tria, settings.mesh.degree, materials, cs);
      // Every run times the active set's stages (assembly, preconditioner,
      // solves, updates) beside the scene's own.
      contact->set_timer(timing);

      std::set<dealii::types::material_id> discs;
      for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
        discs.insert(ids::disc(d));
      std::vector<contact::MasterCylinder> pins(settings.geometry.n_pins);
      for (unsigned int j = 0; j < pins.size(); ++j)
        pins[j] = {geo.pin_centre(j),
                   settings.geometry.pin_radius,
                   ids::pin(j),
                   ids::pin_surface};
      contact->set_contact(discs, ids::flank, pins, pin_model->deformable());
      pin_model->configure(*contact);
    }



    template <int dim>
    double
    StageScene<dim>::width_scale() const
    {
      return dim == 2 ? settings.geometry.tooth_width : 1.;
    }



    template <int dim>
    double
    StageScene<dim>::model_torque(const double torque) const
    {
      return torque * u::Nmm_per_Nm / width_scale();
    }



    template <int dim>
    double
    StageScene<dim>::stage_torque(const double reaction) const
    {
      return reaction * width_scale() * u::Nm_per_Nmm;
    }



    template <int dim>
    void
    StageScene<dim>::setup_system()
    {
      dealii::TimerOutput::Scope t(timing, "setup system");
      contact->setup();
      const auto &el = contact->elasticity();
      const auto &fe = el.finite_element();
      const auto  load_id =
        settings.scene.load_introduction == Scene::LoadIntroduction::bore ?
           ids::bore :
           ids::crank_hole;
      auto values = elasticity::support_point_values(el);
      std::vector<dealii::types::global_dof_index> indices(
        fe.n_dofs_per_cell());
      std::vector<dealii::types::global_dof_index>      fixed;
      std::map<dealii::types::global_dof_index, double> load;
      // Every cell this rank holds: the supports and loads of its locally
      // relevant DoFs (the constraints keep only those).
      for (const auto &cell : el.dof_handler().active_cell_iterators())
        {
          if (cell->is_artificial())
            continue;
          cell->get_dof_indices(indices);
          pin_model->held_dofs(cell, indices, values, fixed);
          if (!ids::is_disc(cell->material_id()))
            continue;
          // The disc's load surface turns by beta about the disc's centre.
          const dealii::Point<2> centre =
            geo.disc_centre(cell->material_id(), psi);
          for (const unsigned int f : cell->face_indices())
            {
              if (!cell->face(f)->at_boundary() ||
                  cell->face(f)->boundary_id() != load_id)
                continue;
              values.reinit(cell);
              for (unsigned int i = 0; i < indices.size(); ++i)
                if (fe.has_support_on_face(i, f))
                  {
                    const auto [comp, node] = fe.system_to_component_index(i);
                    load[indices[i]] =
                      unit_rotation(centre,
                                    values.quadrature_point(node),
                                    comp);
                  }
            }
        }
      contact->set_fixed_dofs(fixed);
      contact->set_load(load);
      unsigned int hanging = 0;
      for (const auto &s : contact->slave_nodes())
        hanging += s.hanging;
      pcout << "  contact: pins " << pin_model->name() << ", " << el.n_dofs()
            << " DoFs (Q" << fe.degree << "), " << contact->slave_nodes().size()
            << " candidate nodes (" << hanging << " hanging)"
            << (contact->tied_nodes().empty() ?
                  std::string() :
                  ", " + std::to_string(contact->tied_nodes().size()) +
                    " seat nodes glued to the pins")
            << std::endl;
    }



    template <int dim>
    bool
    StageScene<dim>::plain_amg() const
    {
      const auto &c = settings.contact;
      return c.linear_solver == elasticity::LinearSolver::cg_amg &&
             c.hierarchy(dim) == elasticity::AMGHierarchy::plain_w;
    }



    template <int dim>
    CostInputs
    StageScene<dim>::cost_inputs(
      const dealii::types::global_dof_index n_dofs) const
    {
      CostInputs in{dim,
                    settings.scene.n_discs,
                    n_dofs,
                    settings.mesh.degree,
                    0,
                    dealii::Utilities::MPI::n_mpi_processes(comm),
                    false};
      in.plain_amg     = plain_amg();
      in.heap_released = elasticity::mmap_threshold() != 0;
      return in;
    }



    template <int dim>
    void
    StageScene<dim>::announce_cost() const
    {
      // The DoFs exist, the matrices not yet (they are allocated at the
      // first solve): the last moment to stop a run that cannot fit.
      const auto &m       = settings.mesh;
      CostInputs  in      = cost_inputs(contact->elasticity().n_dofs());
      in.adaptive_cycles  = m.adaptive_cycles;
      in.error_estimate   = m.error.estimates(dim);
      in.bulk_estimate    = m.error.bulk_level(dim);
      const auto estimate = estimate_cost(in);
      pcout << "  " << estimate.line();
      if (m.error.target_accuracy > 0)
        {
          // A state that misses the target on the mesh asked for costs
          // more: say how much at worst, before the user waits for it.
          in.adaptive_cycles += m.error.max_cycles;
          std::ostringstream worst;
          worst << std::setprecision(2) << estimate_cost(in).seconds_per_state;
          pcout << ", at most " << worst.str()
                << " s if Target accuracy takes all its " << m.error.max_cycles
                << " cycles";
        }
      pcout << std::endl;
      // The bulk level is skipped when it would not fit (refinement_fits):
      // only the mesh asked for must fit.
      in.adaptive_cycles = m.adaptive_cycles;
      in.bulk_estimate   = false;
      check_memory(estimate_cost(in), available_memory_bytes(comm), m);
    }



    template <int dim>
    void
    StageScene<dim>::announce_resolution(const double torque) const
    {
      const auto &e = settings.mesh.error;
      if (settings.rotation_control || torque == 0 || e.estimates(dim))
        return;
      // The analytical model's largest pin force is within a few per cent
      // of the FE model's (doc/scene-guide.md) and n goes as its square
      // root; but it may sit on a neighbour of the FE model's most loaded
      // pin, whose flank curvature, so Hertz width, differs (by about
      // 20 % in n on the seed).
      const results::StageState a =
        model.stage_state(model.solve(psi, torque, 0.), psi);
      const auto most = a.most_loaded_pin();
      if (most == a.pins.end() || !(most->fn > 0))
        return;
      const double h =
        flank_node_spacing(most->disc, most->pin, most->contact_point);
      if (!(h > 0))
        return;
      const double       n = 2. * most->hertz_halfwidth / h;
      const double       r = results::resolution_constant / (n * n);
      std::ostringstream line;
      line << "  contact resolution expected at " << torque
           << " N m: " << std::setprecision(2) << n
           << " node(s) across the Hertz width of the most loaded pin (disc "
           << most->disc << " pin " << most->pin << ", "
           << std::lround(most->fn) << " N in the analytical model), pin "
           << "forces to about " << 100. * r << " %";
      if (e.warning_threshold > 0 && r > e.warning_threshold)
        line << ": above Mesh/Warning threshold, so the states will be "
                "flagged; about "
             << std::ceil(std::log(r / e.warning_threshold) / std::log(4.))
             << " more Contact refinements would resolve it";
      pcout << line.str() << std::endl;
    }



    template <int dim>
    void
    StageScene<dim>::compute_rotation_field()
    {
      const auto &el     = contact->elasticity();
      const auto &fe     = el.finite_element();
      const auto &owned  = el.locally_owned_dofs();
      auto        values = elasticity::support_point_values(el);
      std::vector<dealii::types::global_dof_index> indices(
        fe.n_dofs_per_cell());
      rotation.reinit(owned, comm);
      for (const auto &cell : el.dof_handler().active_cell_iterators())
        {
          if (!cell->is_locally_owned() || !ids::is_disc(cell->material_id()))
            continue;
          const dealii::Point<2> c =
            geo.disc_centre(cell->material_id(), psi_mesh);
          values.reinit(cell);
          cell->get_dof_indices(indices);
          for (unsigned int i = 0; i < indices.size(); ++i)
            if (owned.is_element(indices[i]))
              {
                const auto [comp, node] = fe.system_to_component_index(i);
                rotation[indices[i]] =
                  unit_rotation(c, values.quadrature_point(node), comp);
              }
        }
      rotation.compress(dealii::VectorOperation::insert);
    }



    template <int dim>
    void
    StageScene<dim>::place_discs(const double psi_now)
    {
      dealii::TimerOutput::Scope scope(timing, "place discs");
      psi                   = psi_now;
      const auto        &g  = geo;
      const unsigned int nd = settings.scene.n_discs;
      const double       p0 = psi_mesh;
      contact->set_placement(
        [&g, nd, p0, psi_now](const dealii::types::material_id body,
                              const dealii::Point<dim>        &x) {
          if (body >= nd)
            return x;
          const dealii::Point<2> moved =
            g.to_housing(body,
                         psi_now,
                         g.to_disc(body, p0, dealii::Point<2>(x[0], x[1])));
          dealii::Point<dim> y = x;
          y[0]                 = moved[0];
          y[1]                 = moved[1];
          return y;
        });
      contact->update_geometry();
    }



    template <int dim>
    contact::ContactState
    StageScene<dim>::solve_state(const double load)
    {
      dealii::TimerOutput::Scope t(timing, "solve (active set)");
      std::ostringstream         label;
      label << "crank angle " << psi * u::deg_per_rad << " deg, ";
      if (settings.rotation_control)
        {
          label << "rotation " << load << " rad";
          return contact->solve_displacement(load, label.str());
        }
      label << "torque " << load << " N m";
      return contact->solve_load(model_torque(load), label.str());
    }



    template <int dim>
    unsigned int
    StageScene<dim>::level_cap() const
    {
      // The a-priori refinements, the adaptive cycles, and what the target
      // accuracy may add.
      const auto  &m     = settings.mesh;
      unsigned int extra = 0;
      if (m.error.target_accuracy > 0)
        extra += m.error.max_cycles;
      return m.global_refinements + m.contact_refinements + m.adaptive_cycles +
             extra;
    }



    template <int dim>
    unsigned int
    StageScene<dim>::contact_level() const
    {
      return tria->n_global_levels() - 1 - settings.mesh.global_refinements;
    }



    template <int dim>
    void
    StageScene<dim>::rebuild(const ActiveSetSnapshot<dim> &snapshot)
    {
      setup_system();
      compute_rotation_field();
      contact->transfer_active_set(snapshot);
    }



    template <int dim>
    bool
    StageScene<dim>::refine_at_contacts()
    {
      dealii::TimerOutput::Scope t(timing, "refine at contacts");
      // Cells of any body next to an active node, up to the level cap.
      const unsigned int              cap = level_cap();
      std::vector<dealii::Point<dim>> points;
      for (const unsigned int i : contact->active_set())
        points.push_back(contact->slave_nodes()[i].position);
      unsigned int flagged = 0;
      for (const auto &cell : tria->active_cell_iterators())
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
      tria->prepare_coarsening_and_refinement();
      if (!refinement_fits())
        {
          for (const auto &cell : tria->active_cell_iterators())
            cell->clear_refine_flag();
          return false;
        }
      const auto snapshot = contact->active_set_snapshot();
      tria->execute_coarsening_and_refinement();
      rebuild(snapshot);
      return true;
    }



    template <int dim>
    bool
    StageScene<dim>::refinement_fits(const std::string &what)
    {
      // Each cell counted by its owner (a shared mesh has the same flags
      // on every rank, a distributed one on the owner's cells).
      std::size_t flagged = 0;
      for (const auto &cell : tria->active_cell_iterators())
        if (cell->is_locally_owned() && cell->refine_flag_set())
          ++flagged;
      flagged            = dealii::Utilities::MPI::sum(flagged, comm);
      const double cells = tria->n_global_active_cells();
      const double grown = (cells + ((1u << dim) - 1) * flagged) / cells;
      const auto   dofs  = static_cast<dealii::types::global_dof_index>(
        grown * contact->elasticity().n_dofs());
      const double needed    = estimate_cost(cost_inputs(dofs)).memory_bytes;
      const double available = available_memory_bytes(comm);
      if (needed <= available)
        return true;
      std::ostringstream why;
      why << std::setprecision(3) << what << " (" << flagged << " cells, about "
          << dofs << " DoFs) would need an estimated " << needed / 1e9
          << " GB, more than the " << available / 1e9
          << " GB available (MemAvailable and what the run holds)";
      memory_stop = why.str();
      pcout << "  refinement stopped: " << memory_stop
            << "; the state keeps the mesh it was solved on" << std::endl;
      return false;
    }



    template <int dim>
    void
    StageScene<dim>::SolveCost::add(const contact::ContactState &result)
    {
      iterations += result.iterations;
      linear += result.linear_iterations;
      setups += result.preconditioner_setups;
    }



    template <int dim>
    results::StageState
    StageScene<dim>::solve_level(const double load, SolveCost &cost)
    {
      const contact::ContactState result = solve_state(load);
      cost.add(result);
      return state(result, load);
    }



    template <int dim>
    std::set<dealii::CellId>
    StageScene<dim>::coarsen_finest_level()
    {
      // The finest cells all lie at the contacts (only the contact
      // refinements reach that level); their parents are remembered, so
      // that refining those again restores the mesh exactly.
      const unsigned int top = tria->n_global_levels() - 1;
      for (const auto &cell : tria->active_cell_iterators())
        if (!cell->is_artificial() &&
            static_cast<unsigned int>(cell->level()) == top)
          cell->set_coarsen_flag();
      tria->prepare_coarsening_and_refinement();
      const auto parents = gather_cell_ids(comm, *tria, [](const auto &cell) {
        return cell->coarsen_flag_set() ?
                 std::optional<dealii::CellId>(cell->parent()->id()) :
                 std::nullopt;
      });
      tria->execute_coarsening_and_refinement();
      return parents;
    }



    template <int dim>
    void
    StageScene<dim>::refine_cells(const std::set<dealii::CellId> &cells)
    {
      for (const auto &cell : tria->active_cell_iterators())
        if (!cell->is_artificial() && cells.count(cell->id()) > 0)
          cell->set_refine_flag();
      tria->execute_coarsening_and_refinement();
    }



    template <int dim>
    bool
    StageScene<dim>::solve_coarser_levels(
      const double                      load,
      std::vector<results::StageState> &coarser,
      SolveCost                        &cost)
    {
      const unsigned int n = mesh::ErrorControl::coarser_levels;
      if (tria->n_global_levels() - 1 < settings.mesh.global_refinements + n)
        return false;
      const auto n_cells  = tria->n_global_active_cells();
      const auto original = contact->active_set_snapshot();
      std::vector<std::set<dealii::CellId>> parents;
      {
        dealii::TimerOutput::Scope t(timing, "error estimate: coarsen");
        for (unsigned int k = 0; k < n; ++k)
          parents.push_back(coarsen_finest_level());
        rebuild(original);
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
              coarser.push_back(solve_level(load, cost));
              snapshot = contact->active_set_snapshot();
            }
          catch (const dealii::ExceptionBase &e)
            {
              std::ostringstream message;
              e.print_info(message);
              coarse_failure = trimmed(message.str());
              solved         = false;
            }
          catch (const std::exception &e)
            {
              coarse_failure = trimmed(e.what());
              solved         = false;
            }
          dealii::TimerOutput::Scope t(timing, "error estimate: coarsen");
          if (!solved)
            {
              for (unsigned int j = k + 1; j-- > 0;)
                refine_cells(parents[j]);
              rebuild(original);
              break;
            }
          refine_cells(parents[k]);
          rebuild(snapshot);
        }
      AssertThrow(tria->n_global_active_cells() == n_cells,
                  dealii::ExcMessage("the error estimate's coarser levels did "
                                     "not refine back to the mesh asked for."));
      return solved;
    }



    template <int dim>
    bool
    StageScene<dim>::solve_bulk_level(const double         load,
                                      results::StageState &bulk,
                                      SolveCost           &cost)
    {
      const auto n_cells  = tria->n_global_active_cells();
      const auto original = contact->active_set_snapshot();
      // The contact levels' estimate coarsens the finest levels and so
      // sees the error of the cells on them; every other cell is the same
      // on all its levels. Those are refined: the cells at the global
      // refinement level and the graded halo of levels between it and
      // the contacts (that halo alone put pin forces 1-3 % off with an
      // estimate of 0.3-0.5 %, against Q2: doc/error-estimate.md §5).
      const unsigned int       top  = tria->n_global_levels() - 1;
      const unsigned int       seen = mesh::ErrorControl::coarser_levels;
      std::set<dealii::CellId> refined;
      {
        dealii::TimerOutput::Scope t(timing, "error estimate: bulk refine");
        for (const auto &cell : tria->active_cell_iterators())
          if (!cell->is_artificial() &&
              static_cast<unsigned int>(cell->level()) + seen <= top)
            cell->set_refine_flag();
        tria->prepare_coarsening_and_refinement();
        if (!refinement_fits("the bulk level's refinement"))
          {
            for (const auto &cell : tria->active_cell_iterators())
              cell->clear_refine_flag();
            return false;
          }
        refined = gather_cell_ids(comm, *tria, [](const auto &cell) {
          return cell->refine_flag_set() ?
                   std::optional<dealii::CellId>(cell->id()) :
                   std::nullopt;
        });
        tria->execute_coarsening_and_refinement();
        rebuild(original);
      }
      bool solved = true;
      try
        {
          bulk = solve_level(load, cost);
        }
      catch (const std::exception &e)
        {
          coarse_failure = trimmed(e.what());
          solved         = false;
        }
      dealii::TimerOutput::Scope t(timing, "error estimate: bulk refine");
      // Back to the mesh asked for: coarsen the children of the cells
      // refined above.
      for (const auto &cell : tria->active_cell_iterators())
        if (!cell->is_artificial() && cell->level() > 0 &&
            refined.count(cell->parent()->id()) > 0)
          cell->set_coarsen_flag();
      tria->execute_coarsening_and_refinement();
      rebuild(original);
      AssertThrow(tria->n_global_active_cells() == n_cells,
                  dealii::ExcMessage("the error estimate's bulk level did "
                                     "not coarsen back to the mesh asked "
                                     "for."));
      return solved;
    }



    template <int dim>
    std::optional<results::BulkError>
    StageScene<dim>::measure_bulk_error(const double               load,
                                        const results::StageState &fine,
                                        SolveCost                 &cost)
    {
      results::StageState refined;
      if (solve_bulk_level(load, refined, cost))
        return results::bulk_error(refined, fine);
      pcout << "  no bulk error estimate: "
            << (memory_stop.empty() ? coarse_failure : memory_stop)
            << std::endl;
      // Neither is about the contact levels reported later.
      memory_stop.clear();
      coarse_failure.clear();
      return std::nullopt;
    }



    template <int dim>
    void
    StageScene<dim>::remeasure_bulk_error(
      const double                            load,
      const std::vector<results::StageState> &levels,
      results::StageState                    &fine,
      SolveCost                              &cost)
    {
      // The cycles added a graded halo around the contacts, finer than the
      // first mesh there but not seen by the contact levels: the part the
      // state reports is its own mesh's. If that level does not fit, the
      // first mesh's part stays (measure_bulk_error() says so), and what
      // stopped the cycles is still reported.
      const std::string stop    = memory_stop;
      const std::string failure = coarse_failure;
      const auto        bulk    = measure_bulk_error(load, fine, cost);
      memory_stop               = stop;
      coarse_failure            = failure;
      if (!bulk)
        return;
      results::set_error_estimate(levels[0], levels[1], fine, contact_level());
      results::add_bulk_error(*bulk, fine);
    }



    template <int dim>
    bool
    StageScene<dim>::refine_again(const unsigned int         cycle,
                                  const bool                 have_coarse,
                                  const results::StageState &fine) const
    {
      const auto &m = settings.mesh;
      if (cycle < m.adaptive_cycles)
        return true;
      return m.error.target_accuracy > 0 && have_coarse &&
             fine.error.largest() > m.error.target_accuracy &&
             cycle < m.adaptive_cycles + m.error.max_cycles;
    }



    template <int dim>
    void
    StageScene<dim>::initialise_active_set(const double load)
    {
      // The nodes that the analytical model's rotation pushes into the pins
      // (an empty set leaves the discs free).
      analytic::LoadState analytical;
      if (!settings.rotation_control)
        analytical = model.solve(psi, load, 0.);
      const double beta =
        settings.rotation_control ? load : analytical.rotation;
      const std::vector<FirstSetReach> reach =
        settings.rotation_control ||
            settings.contact.first_set == contact::FirstActiveSet::overlap ?
          std::vector<FirstSetReach>() :
          first_set_reach(model.stage_state(analytical, psi));
      const unsigned int zp = settings.geometry.n_pins;
      contact->initialise_active_set([&](const contact::SlaveNode<dim> &s) {
        const dealii::Point<2> c = geo.disc_centre(s.body, psi);
        const double n_dot_u = beta * (s.normal[1] * (s.position[0] - c[0]) -
                                       s.normal[0] * (s.position[1] - c[1]));
        if (!(s.gap0 + n_dot_u < 0))
          return false;
        if (reach.empty())
          return true;
        const FirstSetReach &r = reach[s.body * zp + s.cylinder];
        const double         a =
          angle_about(s.position, geo.pin_centre(s.cylinder), r.angle);
        return settings.geometry.pin_radius * std::abs(a) <= r.arc;
      });
    }



    template <int dim>
    std::vector<typename StageScene<dim>::FirstSetReach>
    StageScene<dim>::first_set_reach(
      const results::StageState &analytical) const
    {
      // The rigid rotation overlaps a pin about sqrt(2) times as wide as the
      // contact it makes, and the analytical model's rotation overlaps more
      // nodes than the FE model ends with (1782 against 817 in the 3D seed
      // case, doc/solver-reuse.md), and the surplus costs active-set
      // iterations of the state. The Hertz width of the analytical pin force
      // bounds the set instead, widened by half a node spacing: a node
      // whose half of the flank reaches into the contact carries pressure.
      // One node spacing at least, as on a mesh that does not resolve the
      // width the overlap picks the right nodes.
      const unsigned int         zp = settings.geometry.n_pins;
      std::vector<FirstSetReach> reach(settings.scene.n_discs * zp);
      for (const results::PinState &p : analytical.pins)
        {
          const dealii::Point<2> c = geo.pin_centre(p.pin);
          FirstSetReach         &r = reach[p.disc * zp + p.pin];
          r.angle                  = angle_about(p.contact_point, c, 0.);
          const double h = flank_node_spacing(p.disc, p.pin, p.contact_point);
          r.arc          = std::max(p.hertz_halfwidth + 0.5 * h, h);
        }
      return reach;
    }



    template <int dim>
    results::StageState
    StageScene<dim>::solve(const double load)
    {
      const auto start = std::chrono::steady_clock::now();
      // The previous state's active set is the warm start, unless the load
      // changed sign (the other flanks carry it): then the analytical
      // model's rotation picks the new side's pins.
      if (!warm || load * warm_load < 0)
        {
          initialise_active_set(load);
          warm = true;
        }
      if (load != 0) // a zero load has no side
        warm_load = load;
      const bool estimate = settings.mesh.error.estimates(dim);
      coarse_failure.clear();
      memory_stop.clear();
      SolveCost                        cost;
      std::vector<results::StageState> levels; // coarsest first
      bool have_coarse = estimate && solve_coarser_levels(load, levels, cost);
      results::StageState fine = solve_level(load, cost);
      if (have_coarse)
        results::set_error_estimate(levels[0],
                                    levels[1],
                                    fine,
                                    contact_level());
      std::optional<results::BulkError> bulk;
      if (have_coarse && settings.mesh.error.bulk)
        bulk = measure_bulk_error(load, fine, cost);
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
          fine = solve_level(load, cost);
          if (have_coarse)
            results::set_error_estimate(levels[0],
                                        levels[1],
                                        fine,
                                        contact_level());
          if (bulk)
            results::add_bulk_error(*bulk, fine);
        }
      if (bulk && cycle > 0)
        remeasure_bulk_error(load, levels, fine, cost);
      if (!coarse_failure.empty() && !fine.error.available())
        fine.error.failure = coarse_failure;
      report_accuracy(fine);
      fine.iterations            = cost.iterations;
      fine.linear_iterations     = cost.linear;
      fine.preconditioner_setups = cost.setups;
      fine.peak_memory_MB        = postprocess::peak_memory_MB(comm);
      fine.wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
      return fine;
    }



    template <int dim>
    void
    StageScene<dim>::report_accuracy(const results::StageState &s) const
    {
      const double target = settings.mesh.error.target_accuracy;
      if (target == 0 || !s.error.available())
        return;
      pcout << "  target accuracy " << target << ": "
            << (s.error.largest() <= target ? "reached" : "NOT reached")
            << " at contact level " << s.error.contact_level << " (" << s.dofs
            << " DoFs), largest estimate " << s.error.largest()
            << (s.error.largest() <= target ?
                  std::string() :
                !memory_stop.empty() ?
                  "; " + memory_stop :
                  "; Mesh/Maximum accuracy cycles (now " +
                    std::to_string(settings.mesh.error.max_cycles) +
                    ") or Mesh/Contact refinements would "
                    "go further")
            << std::endl;
      if (s.error.largest() > target && s.error.bulk > 0.5 * target)
        pcout << "  the bulk mesh's part of the estimate is " << s.error.bulk
              << ": the target's cycles refine at the "
              << "contacts and do not reduce it; "
              << postprocess::Report::bulk_advice << std::endl;
    }



    template <int dim>
    void
    StageScene<dim>::sum_pin_forces(std::vector<results::PinState> &pins) const
    {
      const unsigned int  zp        = settings.geometry.n_pins;
      const double        scale     = width_scale();
      const auto         &slaves    = contact->slave_nodes();
      const auto         &reactions = contact->slave_reactions();
      std::vector<double> moment(pins.size(), 0.);
      for (const unsigned int i : contact->active_set())
        {
          const auto            &s = slaves[i];
          const unsigned int     k = s.body * zp + s.cylinder;
          const dealii::Point<2> c = geo.disc_centre(s.body, psi);
          // Reactions are in the mesh axes; the disc has turned by delta
          // since the mesh's crank angle (transient runs): housing frame.
          const double delta = geo.disc_rotation(s.body, psi) -
                               geo.disc_rotation(s.body, psi_mesh);
          const double rx = reactions[i][0] * scale,
                       ry = reactions[i][1] * scale;
          const double gx = std::cos(delta) * rx - std::sin(delta) * ry,
                       gy = std::sin(delta) * rx + std::cos(delta) * ry;
          pins[k].fx += gx;
          pins[k].fy += gy;
          ++pins[k].active_nodes;
          moment[k] +=
            (s.position[0] - c[0]) * gy - (s.position[1] - c[1]) * gx;
        }
      for (unsigned int k = 0; k < pins.size(); ++k)
        {
          auto &p = pins[k];
          p.fn    = std::hypot(p.fx, p.fy);
          // The pin's force on the disc resists a positive torque:
          // arm = -(r x F)/|F|.
          if (p.fn > 0)
            p.arm = -moment[k] / p.fn;
        }
    }



    template <int dim>
    double
    StageScene<dim>::takeup_rotation(const int sign) const
    {
      // Rigid take-up (lost motion) of the exact geometry, as in the
      // analytical model: the rotation that closes the first clearance of
      // any disc on the side of the torque's sign.
      double takeup = std::numeric_limits<double>::max();
      for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
        for (const auto &pc : geo.pin_contacts(d, psi))
          if (sign * pc.arm > 1e-9)
            takeup =
              std::min(takeup, std::max(pc.clearance, 0.) / std::abs(pc.arm));
      AssertThrow(takeup < std::numeric_limits<double>::max(),
                  dealii::ExcMessage("no pin can carry a torque of this sign "
                                     "at this crank angle."));
      return takeup;
    }



    template <int dim>
    void
    StageScene<dim>::set_pin_geometry(results::StageState &s) const
    {
      const unsigned int zp = settings.geometry.n_pins;
      for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
        for (const auto &pc : geo.pin_contacts(d, psi))
          {
            auto &p = s.pins[d * zp + pc.pin];
            if (p.fn == 0)
              p.arm = pc.arm;
            p.clearance     = pc.clearance;
            p.phase         = pc.phase;
            p.contact_point = pc.contact_point;
            p.approach      = s.rotation * pc.arm - pc.clearance;
            p.hertz_halfwidth =
              analytic::stage_hertz_half_width(p.fn,
                                               pc.curvature_radius,
                                               settings.geometry,
                                               settings.material,
                                               settings.scene);
            if (p.fn > 0)
              {
                p.contact_halfwidth =
                  contact_halfwidth(d, pc.pin, pc.contact_point);
                const double h =
                  flank_node_spacing(d, pc.pin, pc.contact_point);
                if (h > 0)
                  p.hertz_nodes = 2. * p.hertz_halfwidth / h;
              }
            analytic::set_hertz_stresses(p,
                                         settings.geometry.tooth_width,
                                         settings.material.disc.poissons_ratio);
            s.reaction_torque += p.fn * p.arm * u::Nm_per_Nmm;
          }
    }



    template <int dim>
    results::StageState
    StageScene<dim>::zero_torque_limit(const int side) const
    {
      // T -> 0 on one side: the discs turned by the take-up towards that
      // side, every pin just touching or clear, no force, no solve.
      const unsigned int  zp = settings.geometry.n_pins;
      results::StageState s;
      s.crank     = psi;
      s.torque    = 0;
      s.takeup    = side * takeup_rotation(side);
      s.rotation  = s.takeup;
      s.k_tangent = std::numeric_limits<double>::quiet_NaN();
      s.dofs      = contact->elasticity().n_dofs();
      s.pins.resize(settings.scene.n_discs * zp);
      for (unsigned int k = 0; k < s.pins.size(); ++k)
        {
          s.pins[k].disc = k / zp;
          s.pins[k].pin  = k % zp;
        }
      set_pin_geometry(s);
      s.peak_memory_MB = postprocess::peak_memory_MB(comm);
      return s;
    }



    template <int dim>
    void
    StageScene<dim>::set_peak_pressures(
      std::vector<results::PinState> &pins) const
    {
      // Nodal pressure = normal reaction / the node's share of the slave
      // surface (as in the VTU field); the model's reactions are already
      // per unit thickness in 2D, so no width scaling.
      const unsigned int zp        = settings.geometry.n_pins;
      const auto        &slaves    = contact->slave_nodes();
      const auto        &reactions = contact->slave_reactions();
      for (const unsigned int i : contact->active_set())
        {
          const auto &s = slaves[i];
          if (s.weight <= 0)
            continue;
          auto &p = pins[s.body * zp + s.cylinder];
          p.max_pressure =
            std::max(p.max_pressure, (reactions[i] * s.normal) / s.weight);
        }
    }



    template <int dim>
    std::vector<std::pair<double, bool>>
    StageScene<dim>::pair_node_angles(
      const unsigned int      d,
      const unsigned int      j,
      const dealii::Point<2> &contact_point) const
    {
      const auto            &slaves = contact->slave_nodes();
      const auto            &active = contact->active_set();
      const dealii::Point<2> c      = geo.pin_centre(j);
      const double           a0     = angle_about(contact_point, c, 0.);
      std::vector<std::pair<double, bool>> angles;
      for (unsigned int i = 0; i < slaves.size(); ++i)
        if (slaves[i].body == d && slaves[i].cylinder == j)
          angles.emplace_back(angle_about(slaves[i].position, c, a0),
                              active.count(i) > 0);
      return angles;
    }



    template <int dim>
    double
    StageScene<dim>::contact_halfwidth(
      const unsigned int      d,
      const unsigned int      j,
      const dealii::Point<2> &contact_point) const
    {
      // Half the arc between the outermost active nodes of this pair, plus
      // half a node spacing on each side.
      const auto angles = pair_node_angles(d, j, contact_point);
      double     lo = 1e300, hi = -1e300, spacing = 1e300;
      for (const auto &[a, is_active] : angles)
        if (is_active)
          {
            lo = std::min(lo, a);
            hi = std::max(hi, a);
          }
      if (hi < lo)
        return 0.;
      for (const auto &[a, is_active] : angles)
        if (a > hi + 1e-12 || a < lo - 1e-12)
          spacing =
            std::min(spacing, std::min(std::abs(a - hi), std::abs(a - lo)));
      if (spacing > 1e200)
        spacing = 0;
      return settings.geometry.pin_radius * (0.5 * (hi - lo) + 0.5 * spacing);
    }



    template <int dim>
    double
    StageScene<dim>::flank_node_spacing(
      const unsigned int      d,
      const unsigned int      j,
      const dealii::Point<2> &contact_point) const
    {
      // The distinct angles (3D: the axial nodes of a flank line share
      // one), sorted; the contact point lies at angle 0.
      std::vector<double> a;
      for (const auto &[angle, is_active] :
           pair_node_angles(d, j, contact_point))
        a.push_back(angle);
      std::sort(a.begin(), a.end());
      a.erase(std::unique(a.begin(),
                          a.end(),
                          [](const double x, const double y) {
                            return std::abs(x - y) < 1e-9;
                          }),
              a.end());
      if (a.size() < 2)
        return 0.;
      const auto nearest = std::min_element(a.begin(),
                                            a.end(),
                                            [](const double x, const double y) {
                                              return std::abs(x) < std::abs(y);
                                            });
      double     gap     = 1e300;
      if (nearest != a.begin())
        gap = std::min(gap, *nearest - *std::prev(nearest));
      if (std::next(nearest) != a.end())
        gap = std::min(gap, *std::next(nearest) - *nearest);
      return settings.geometry.pin_radius * gap;
    }



    template <int dim>
    results::StageState
    StageScene<dim>::state(const contact::ContactState &result,
                           const double                 load) const
    {
      dealii::TimerOutput::Scope t(timing, "pin forces");
      const unsigned int         zp = settings.geometry.n_pins;
      const unsigned int         nd = settings.scene.n_discs;
      results::StageState        s;
      s.crank = psi;
      s.torque =
        settings.rotation_control ? stage_torque(result.reaction) : load;
      s.rotation              = result.beta;
      s.k_tangent             = result.tangent * width_scale() * u::Nm_per_Nmm;
      s.dofs                  = contact->elasticity().n_dofs();
      s.iterations            = result.iterations;
      s.linear_iterations     = result.linear_iterations;
      s.preconditioner_setups = result.preconditioner_setups;
      s.cycles_broken         = result.cycles_broken;
      s.cycle_tension         = result.cycle_tension;
      s.pins.resize(nd * zp);
      for (unsigned int d = 0; d < nd; ++d)
        for (unsigned int j = 0; j < zp; ++j)
          {
            s.pins[d * zp + j].disc = d;
            s.pins[d * zp + j].pin  = j;
          }
      sum_pin_forces(s.pins);
      set_pin_geometry(s);
      set_peak_pressures(s.pins);
      const int sign = s.torque >= 0 ? 1 : -1;
      s.takeup       = sign * takeup_rotation(sign);
      return s;
    }



    template <int dim>
    ActiveSetSnapshot<dim>
    StageScene<dim>::active_set_snapshot() const
    {
      return contact->active_set_snapshot();
    }



    template <int dim>
    void
    StageScene<dim>::warm_start(const ActiveSetSnapshot<dim> &snapshot)
    {
      contact->transfer_active_set(snapshot);
      warm = !snapshot.empty();
      // The snapshot is of the same load at another crank angle: its side
      // is right, whatever this scene solved last.
      warm_load = 0;
    }



    template <int dim>
    void
    StageScene<dim>::output_results(const unsigned int           step,
                                    postprocess::SolutionRecord &record)
    {
      dealii::TimerOutput::Scope t(timing, "output results");
      const std::string          name = postprocess::SolutionRecord::name(step);
      contact->write_vtu(settings.output_directory, name);
      record.add(step, name + ".pvtu");
    }



    template class StageScene<2>;
    template class StageScene<3>;
  } // namespace stage
} // namespace cycloid

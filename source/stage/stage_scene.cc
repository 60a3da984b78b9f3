#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <cycloid/elasticity/support_points.h>
#include <cycloid/results/cost_figures.h>
#include <cycloid/stage/cost_estimate.h>
#include <cycloid/stage/error_control_loop.h>
#include <cycloid/stage/stage_scene.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace cycloid
{
  namespace stage
  {
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
    } // namespace



    analytic::ModelSettings
    StageSettings::model_settings() const
    {
      return {geometry, material, scene, analytic, bearings};
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
      if (settings.check_cost)
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
      cs.factorisation        = c.factorisation(dim, false);
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
                   geo.pin_radius(j),
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
    results::StageState
    StageScene<dim>::solve_level(const double load)
    {
      return state(solve_state(load), load);
    }



    template <int dim>
    StateBuilder<dim>
    StageScene<dim>::state_builder() const
    {
      return StateBuilder<dim>({settings.geometry,
                                settings.material,
                                settings.scene,
                                psi,
                                psi_mesh,
                                width_scale()},
                               geo,
                               *contact);
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
        return geo.pin_radius(s.cylinder) * std::abs(a) <= r.arc;
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
      const unsigned int         zp      = settings.geometry.n_pins;
      const StateBuilder<dim>    builder = state_builder();
      std::vector<FirstSetReach> reach(settings.scene.n_discs * zp);
      for (const results::PinState &p : analytical.pins)
        {
          const dealii::Point<2> c = geo.pin_centre(p.pin);
          FirstSetReach         &r = reach[p.disc * zp + p.pin];
          r.angle                  = angle_about(p.contact_point, c, 0.);
          const double h =
            builder.flank_node_spacing(p.disc, p.pin, p.contact_point);
          r.arc = std::max(p.hertz_halfwidth + 0.5 * h, h);
        }
      return reach;
    }



    template <int dim>
    results::StageState
    StageScene<dim>::solve(const double load)
    {
      const auto start = results::Clock::now();
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
      ControlledState controlled =
        ErrorControlLoop<dim>(*this, settings.mesh, pcout).solve(load);
      results::StageState &s  = controlled.state;
      s.iterations            = controlled.cost.iterations;
      s.linear_iterations     = controlled.cost.linear;
      s.preconditioner_setups = controlled.cost.setups;
      s.peak_memory_MB        = results::peak_memory_MB(comm);
      s.wall_s                = results::seconds_since(start);
      return s;
    }



    template <int dim>
    results::StageState
    StageScene<dim>::zero_torque_limit(const int side) const
    {
      results::StageState s = state_builder().zero_torque_limit(side);
      s.peak_memory_MB      = results::peak_memory_MB(comm);
      return s;
    }



    template <int dim>
    results::StageState
    StageScene<dim>::state(const contact::ContactState &result,
                           const double                 load) const
    {
      dealii::TimerOutput::Scope t(timing, "pin forces");
      return state_builder().state(result,
                                   settings.rotation_control ?
                                     stage_torque(result.reaction) :
                                     load);
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
    StageScene<dim>::output_results(const std::string &name)
    {
      dealii::TimerOutput::Scope t(timing, "output results");
      contact->write_vtu(settings.output_directory, name);
    }



    template class StageScene<2>;
    template class StageScene<3>;
  } // namespace stage
} // namespace cycloid

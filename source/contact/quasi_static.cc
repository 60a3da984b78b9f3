#include <deal.II/base/exceptions.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/quadrature.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <cycloid/analytic/pair_stiffness.h>
#include <cycloid/analytic/stage_model.h>
#include <cycloid/contact/pin_model.h>
#include <cycloid/contact/quasi_static.h>
#include <cycloid/mesh/stage_mesh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

namespace cycloid
{
  namespace contact
  {
    namespace ids = mesh::ids;
    using Scene   = parameters::SceneParameters;



    template <int dim>
    QuasiStatic<dim>::QuasiStatic(const parameters::AllParameters &parameters,
                                  const double                     psi,
                                  const MPI_Comm                   comm,
                                  const double                     sweep)
      : prm(parameters)
      , comm(comm)
      , psi(psi)
      , psi_mesh(psi)
      , sweep(sweep)
      , geo(parameters.geometry)
      , pcout(std::cout, dealii::Utilities::MPI::this_mpi_process(comm) == 0)
      , timer(comm,
              pcout,
              dealii::TimerOutput::never,
              dealii::TimerOutput::wall_times)
      , tria(comm,
             dealii::Triangulation<dim>::limit_level_difference_at_vertices,
             false,
             dealii::parallel::shared::Triangulation<dim>::partition_metis)
    {
      AssertThrow(prm.scene.load_introduction !=
                      Scene::LoadIntroduction::crank_holes ||
                    prm.geometry.n_crank_holes > 0,
                  dealii::ExcMessage(
                    "Scene/Load introduction = crank holes needs "
                    "Geometry/Number of crank holes > 0 (the disc would have "
                    "no load surface); use Load introduction = bore."));
      pin_model = create_pin_model<dim>(prm);
      make_grid();

      std::map<dealii::types::material_id, parameters::ElasticMaterial>
        materials;
      for (unsigned int d = 0; d < prm.scene.n_discs; ++d)
        materials[ids::disc(d)] = prm.material.disc;
      pin_model->add_materials(materials);

      ContactSettings settings;
      settings.max_iterations     = prm.contact.max_active_set_iterations;
      settings.search_distance    = prm.contact.search_distance;
      settings.solver_tolerance   = prm.contact.solver_tolerance;
      settings.residual_tolerance = prm.contact.residual_tolerance;
      settings.formulation        = prm.contact.formulation == "mortar" ?
                                      Formulation::mortar :
                                      Formulation::node_to_surface;
      settings.solver             = prm.contact.linear_solver == "direct" ?
                                      elasticity::LinearSolver::direct :
                                    prm.contact.linear_solver == "cg-amg-translations" ?
                                      elasticity::LinearSolver::cg_amg_translations_only :
                                      elasticity::LinearSolver::cg_amg;
      contact                     = std::make_unique<ContactProblem<dim>>(tria,
                                                      prm.mesh.degree,
                                                      materials,
                                                      settings);

      std::set<dealii::types::material_id> discs;
      for (unsigned int d = 0; d < prm.scene.n_discs; ++d)
        discs.insert(ids::disc(d));
      std::vector<MasterCylinder> pins(prm.geometry.n_pins);
      for (unsigned int j = 0; j < pins.size(); ++j)
        pins[j] = {geo.pin_centre(j),
                   prm.geometry.pin_radius,
                   ids::pin(j),
                   ids::pin_surface};
      contact->set_contact(discs, ids::flank, pins, pin_model->deformable());
      pin_model->configure(*contact);
      setup_system();
    }



    template <int dim>
    double
    QuasiStatic<dim>::width_scale() const
    {
      return dim == 2 ? prm.geometry.tooth_width : 1.;
    }



    template <int dim>
    void
    QuasiStatic<dim>::make_grid()
    {
      dealii::TimerOutput::Scope t(timer, "make grid");
      mesh::create_stage_mesh(
        mesh::MeshSettings{prm.geometry, prm.scene, prm.mesh},
        mesh::MeshRequest{psi,
                          sweep,
                          prm.mesh.refine_loaded_side_only ?
                            mesh::common_sign(prm.loading.load_values()) :
                            0,
                          prm.mesh.write_msh ?
                            prm.run.output_directory + "/stage.msh" :
                            ""},
        tria);
      pcout << "  mesh: " << dim << "D, " << prm.scene.n_discs << " disc(s), "
            << tria.n_global_active_cells() << " cells" << std::endl;
    }



    template <int dim>
    void
    QuasiStatic<dim>::setup_system()
    {
      dealii::TimerOutput::Scope t(timer, "setup system");
      contact->setup();
      const auto &el = contact->elasticity();
      const auto &fe = el.finite_element();
      const auto  load_id =
        prm.scene.load_introduction == Scene::LoadIntroduction::bore ?
           ids::bore :
           ids::crank_hole;
      // Positions of a cell's nodes (support points on the exact mapping).
      const dealii::Quadrature<dim> nodes(
        fe.base_element(0).get_unit_support_points());
      dealii::FEValues<dim>                        fe_values(el.mapping(),
                                      fe,
                                      nodes,
                                      dealii::update_quadrature_points);
      std::vector<dealii::types::global_dof_index> indices(
        fe.n_dofs_per_cell());
      std::vector<dealii::types::global_dof_index>      fixed;
      std::map<dealii::types::global_dof_index, double> load;
      for (const auto &cell : el.dof_handler().active_cell_iterators())
        {
          const auto m = cell->material_id();
          cell->get_dof_indices(indices);
          pin_model->held_dofs(cell, indices, fe_values, fixed);
          if (m >= prm.scene.n_discs)
            continue;
          // The disc's load surface turns by beta about the disc's centre.
          const dealii::Point<2> centre = geo.disc_centre(m, psi);
          for (const unsigned int f : cell->face_indices())
            {
              if (!cell->face(f)->at_boundary() ||
                  cell->face(f)->boundary_id() != load_id)
                continue;
              fe_values.reinit(cell);
              for (unsigned int i = 0; i < indices.size(); ++i)
                if (fe.has_support_on_face(i, f))
                  {
                    const auto [comp, node] = fe.system_to_component_index(i);
                    const auto &x           = fe_values.quadrature_point(node);
                    // beta z x (x - c): (-(y - cy), x - cx, 0)
                    load[indices[i]] = comp == 0 ? -(x[1] - centre[1]) :
                                       comp == 1 ? x[0] - centre[0] :
                                                   0.;
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
    ContactState
    QuasiStatic<dim>::solve_state(const double load)
    {
      dealii::TimerOutput::Scope t(timer, "solve (active set)");
      std::ostringstream         label;
      label << "crank angle " << psi * 180. / dealii::numbers::PI << " deg, ";
      if (prm.loading.rotation_control)
        {
          label << "rotation " << load << " rad";
          return contact->solve_displacement(load, label.str());
        }
      label << "torque " << load << " N m";
      return contact->solve_load(load * 1e3 / width_scale(), label.str());
    }



    template <int dim>
    void
    QuasiStatic<dim>::refine_at_contacts()
    {
      dealii::TimerOutput::Scope t(timer, "refine at contacts");
      // Cells of any body next to an active node, up to the level that the
      // a-priori refinements plus the adaptive cycles allow.
      const unsigned int cap = prm.mesh.global_refinements +
                               prm.mesh.contact_refinements +
                               prm.mesh.adaptive_cycles;
      std::vector<dealii::Point<dim>> points;
      for (const unsigned int i : contact->active_set())
        points.push_back(contact->slave_nodes()[i].position);
      unsigned int flagged = 0;
      for (const auto &cell : tria.active_cell_iterators())
        {
          if (static_cast<unsigned int>(cell->level()) >= cap)
            continue;
          const auto   c = cell->center();
          const double r = cell->diameter();
          for (const auto &p : points)
            if (p.distance(c) < 2 * r)
              {
                cell->set_refine_flag();
                ++flagged;
                break;
              }
        }
      if (flagged == 0)
        return;
      const auto snapshot = contact->active_set_snapshot();
      tria.execute_coarsening_and_refinement();
      setup_system();
      contact->transfer_active_set(snapshot);
    }



    template <int dim>
    void
    QuasiStatic<dim>::solve(const double                           load,
                            postprocess::StiffnessRow             &row,
                            std::vector<postprocess::PinForceRow> &pins)
    {
      const auto start = std::chrono::steady_clock::now();
      if (!warm)
        {
          // First state: the nodes that the analytical model's rotation
          // pushes into the pins (an empty set leaves the discs free).
          const double beta =
            prm.loading.rotation_control ?
              load :
              analytic::StageModel(prm).solve(psi, load, 0.).rotation;
          contact->initialise_active_set([&](const SlaveNode<dim> &s) {
            const dealii::Point<2> c = geo.disc_centre(s.body, psi);
            const double           n_dot_u =
              beta * (s.normal[1] * (s.position[0] - c[0]) -
                      s.normal[0] * (s.position[1] - c[1]));
            return s.gap0 + n_dot_u < 0;
          });
          warm = true;
        }
      ContactState  state      = solve_state(load);
      unsigned int  iterations = state.iterations;
      unsigned long linear     = state.linear_iterations;
      for (unsigned int cycle = 0; cycle < prm.mesh.adaptive_cycles; ++cycle)
        {
          const auto n = contact->elasticity().n_dofs();
          refine_at_contacts();
          if (contact->elasticity().n_dofs() == n)
            break;
          state = solve_state(load);
          iterations += state.iterations;
          linear += state.linear_iterations;
        }
      {
        dealii::TimerOutput::Scope t(timer, "pin forces");
        const double               torque = prm.loading.rotation_control ?
                                              state.reaction * width_scale() * 1e-3 :
                                              load;
        pin_forces(torque, state, row, pins);
      }
      row.iterations        = iterations;
      row.linear_iterations = linear;
      row.peak_memory_MB    = postprocess::peak_memory_MB(comm);
      row.wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
    }



    template <int dim>
    void
    QuasiStatic<dim>::pin_forces(
      const double                           torque,
      const ContactState                    &state,
      postprocess::StiffnessRow             &row,
      std::vector<postprocess::PinForceRow> &pins) const
    {
      const double       scale     = width_scale();
      const unsigned int zp        = prm.geometry.n_pins;
      const unsigned int nd        = prm.scene.n_discs;
      const auto        &slaves    = contact->slave_nodes();
      const auto        &reactions = contact->slave_reactions();
      // Force of each pin on each disc and its moment about the disc centre.
      std::vector<double> fx(nd * zp, 0.), fy(nd * zp, 0.), moment(nd * zp, 0.);
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
          fx[k] += gx;
          fy[k] += gy;
          moment[k] +=
            (s.position[0] - c[0]) * gy - (s.position[1] - c[1]) * gx;
        }

      row.torque_Nm          = torque;
      row.rotation_rad       = state.beta;
      row.k_tangent          = state.tangent * scale * 1e-3;
      row.k_secant           = torque / state.beta;
      row.dofs               = contact->elasticity().n_dofs();
      row.reaction_torque_Nm = 0;
      row.pins_in_contact    = 0;
      row.max_pin_force_N    = 0;
      pins.clear();
      // Rigid take-up (lost motion) of the exact geometry, as in the
      // analytical model: the rotation that closes the first clearance of
      // any disc.
      double takeup = std::numeric_limits<double>::max();
      std::vector<std::vector<geometry::PinContact>> contacts;
      for (unsigned int d = 0; d < nd; ++d)
        {
          contacts.push_back(geo.pin_contacts(d, psi));
          for (const auto &c : contacts.back())
            if ((torque >= 0 ? c.arm : -c.arm) > 1e-9)
              takeup =
                std::min(takeup, std::max(c.clearance, 0.) / std::abs(c.arm));
        }
      row.takeup_rad       = (torque >= 0 ? 1. : -1.) * takeup;
      row.k_secant_elastic = torque / (state.beta - row.takeup_rad);
      for (unsigned int d = 0; d < nd; ++d)
        for (unsigned int j = 0; j < zp; ++j)
          {
            const unsigned int       k  = d * zp + j;
            const auto              &pc = contacts[d][j];
            postprocess::PinForceRow p;
            p.disc = d;
            p.pin  = j;
            p.fx_N = fx[k] + 0.;
            p.fy_N = fy[k] + 0.;
            p.fn_N = std::hypot(fx[k], fy[k]);
            // The pin's force on the disc resists a positive torque:
            // arm = -(r x F)/|F|.
            p.arm_mm       = p.fn_N > 0 ? -moment[k] / p.fn_N : pc.arm;
            p.clearance_um = pc.clearance * 1e3;
            p.phase_deg    = pc.phase * 180. / dealii::numbers::PI;
            p.contact_x_mm = pc.contact_point[0];
            p.contact_y_mm = pc.contact_point[1];
            p.approach_um  = (state.beta * pc.arm - pc.clearance) * 1e3;
            // Contact half-width: half the arc between the outermost active
            // nodes of this pair, plus half a node spacing on each side.
            const dealii::Point<2> c  = geo.pin_centre(j);
            const double           a0 = std::atan2(pc.contact_point[1] - c[1],
                                         pc.contact_point[0] - c[0]);
            const auto             angle = [&](const SlaveNode<dim> &s) {
              return std::remainder(std::atan2(s.position[1] - c[1],
                                               s.position[0] - c[0]) -
                                      a0,
                                    2. * dealii::numbers::PI);
            };
            double lo = 1e300, hi = -1e300, spacing = 1e300;
            for (const unsigned int i : contact->active_set())
              if (slaves[i].body == d && slaves[i].cylinder == j)
                {
                  lo = std::min(lo, angle(slaves[i]));
                  hi = std::max(hi, angle(slaves[i]));
                }
            if (hi >= lo)
              {
                for (const auto &s : slaves)
                  if (s.body == d && s.cylinder == j)
                    {
                      const double a = angle(s);
                      if (a > hi + 1e-12 || a < lo - 1e-12)
                        spacing = std::min(spacing,
                                           std::min(std::abs(a - hi),
                                                    std::abs(a - lo)));
                    }
                if (spacing > 1e200)
                  spacing = 0;
                p.contact_halfwidth_um = 1e3 * prm.geometry.pin_radius *
                                         (0.5 * (hi - lo) + 0.5 * spacing);
              }
            p.hertz_halfwidth_um =
              1e3 * analytic::hertz_half_width(
                      p.fn_N,
                      prm.geometry.tooth_width,
                      prm.geometry.pin_radius,
                      pc.curvature_radius,
                      prm.material.disc.plane_strain_modulus(),
                      prm.scene.pins == Scene::PinModel::rigid ?
                        0. :
                        prm.material.pin.plane_strain_modulus());
            row.reaction_torque_Nm += p.fn_N * p.arm_mm * 1e-3;
            if (p.fn_N > 0)
              ++row.pins_in_contact;
            row.max_pin_force_N = std::max(row.max_pin_force_N, p.fn_N);
            pins.push_back(p);
          }
    }



    template <int dim>
    void
    QuasiStatic<dim>::output_results(
      const unsigned int                           step,
      std::vector<std::pair<double, std::string>> &records)
    {
      dealii::TimerOutput::Scope t(timer, "output results");
      const std::string          name =
        "solution-" + dealii::Utilities::int_to_string(step, 4);
      contact->write_vtu(prm.run.output_directory, name);
      if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        {
          records.emplace_back(step, name + ".pvtu");
          std::ofstream pvd(prm.run.output_directory + "/solution.pvd");
          dealii::DataOutBase::write_pvd_record(pvd, records);
        }
    }



    template class QuasiStatic<2>;
    template class QuasiStatic<3>;
  } // namespace contact
} // namespace cycloid

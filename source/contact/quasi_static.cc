#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>

#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <cycloid/analytic/stage_model.h>
#include <cycloid/contact/quasi_static.h>
#include <cycloid/mesh/stage_mesh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

namespace cycloid
{
  namespace contact
  {
    namespace ids = mesh::ids;



    QuasiStatic2D::QuasiStatic2D(const parameters::AllParameters &parameters,
                                 const double                     psi,
                                 const MPI_Comm                   comm)
      : prm(parameters)
      , comm(comm)
      , psi(psi)
      , geo(parameters.geometry)
      , tria(comm,
             dealii::Triangulation<2>::limit_level_difference_at_vertices,
             false,
             dealii::parallel::shared::Triangulation<2>::partition_metis)
    {
      AssertThrow(prm.scene.pin_support ==
                    parameters::SceneParameters::PinSupport::axis,
                  dealii::ExcMessage(
                    "Run = quasi-static: only Scene/Pin support = axis is "
                    "implemented so far."));
      mesh::create_stage_mesh(prm, psi, tria);
      std::map<dealii::types::material_id, parameters::ElasticMaterial>
        materials{{ids::disc(0), prm.material.disc}};
      for (unsigned int j = 0; j < prm.geometry.n_pins; ++j)
        materials[ids::pin(j)] = prm.material.pin;
      problem =
        std::make_unique<elasticity::LinearElasticity<2>>(tria, 1, materials);
      problem->setup_system([](dealii::AffineConstraints<double> &) {});
      points = problem->support_points();
      find_slave_nodes();
    }



    void
    QuasiStatic2D::find_slave_nodes()
    {
      const auto load_surface =
        prm.scene.load_introduction ==
            parameters::SceneParameters::LoadIntroduction::bore ?
          ids::bore :
          ids::crank_hole;
      struct Edge
      {
        dealii::Point<2>                             a, b;
        std::vector<dealii::types::global_dof_index> dofs; // ax ay bx by
      };
      std::vector<std::vector<Edge>>    edges(prm.geometry.n_pins);
      std::map<unsigned int, SlaveNode> by_vertex;
      for (const auto &cell : problem->dof_handler().active_cell_iterators())
        {
          if (cell->is_artificial())
            continue;
          if (ids::is_pin(cell->material_id()))
            {
              const unsigned int j = cell->material_id() - ids::pin(0);
              std::vector<dealii::types::global_dof_index> dofs(
                cell->get_fe().n_dofs_per_cell());
              cell->get_dof_indices(dofs);
              pin_dofs.insert(dofs.begin(), dofs.end());
              for (const unsigned int v : cell->vertex_indices())
                if (cell->vertex(v).distance(geo.pin_centre(j)) <
                    prm.scene.pin_core_radius * (1. + 1e-9))
                  for (unsigned int c = 0; c < 2; ++c)
                    core_dofs.insert(cell->vertex_dof_index(v, c));
              for (const unsigned int f : cell->face_indices())
                if (cell->face(f)->at_boundary() &&
                    cell->face(f)->boundary_id() == ids::pin_surface)
                  {
                    const auto face = cell->face(f);
                    edges[j].push_back({face->vertex(0),
                                        face->vertex(1),
                                        {face->vertex_dof_index(0, 0),
                                         face->vertex_dof_index(0, 1),
                                         face->vertex_dof_index(1, 0),
                                         face->vertex_dof_index(1, 1)}});
                  }
              continue;
            }
          for (const unsigned int f : cell->face_indices())
            {
              const auto face = cell->face(f);
              if (!face->at_boundary())
                continue;
              if (face->boundary_id() == load_surface)
                for (const unsigned int v : face->vertex_indices())
                  for (unsigned int c = 0; c < 2; ++c)
                    crank_hole_dofs.insert(face->vertex_dof_index(v, c));
              if (face->boundary_id() != ids::flank)
                continue;
              for (const unsigned int v : face->vertex_indices())
                {
                  const unsigned int index = face->vertex_index(v);
                  if (by_vertex.count(index))
                    continue;
                  const dealii::Point<2> x       = face->vertex(v);
                  unsigned int           nearest = 0;
                  double                 d       = 1e300;
                  for (unsigned int j = 0; j < prm.geometry.n_pins; ++j)
                    if (x.distance(geo.pin_centre(j)) < d)
                      {
                        d       = x.distance(geo.pin_centre(j));
                        nearest = j;
                      }
                  const double gap = d - prm.geometry.pin_radius;
                  if (gap > prm.contact.search_distance)
                    continue;
                  SlaveNode s;
                  s.disc           = 0;
                  s.pin            = nearest;
                  s.position       = x;
                  s.normal         = (x - geo.pin_centre(nearest)) / d;
                  s.gap0           = gap;
                  s.dofs           = {face->vertex_dof_index(v, 0),
                                      face->vertex_dof_index(v, 1)};
                  by_vertex[index] = s;
                }
            }
        }
      std::vector<dealii::types::global_dof_index> masters;
      for (auto &[v, s] : by_vertex)
        {
          if (prm.scene.pins == parameters::SceneParameters::PinModel::elastic)
            {
              // The pin edge that holds the projection P of the node onto
              // the exact cylinder, and P's position t along its chord.
              const dealii::Point<2> P =
                geo.pin_centre(s.pin) +
                prm.geometry.pin_radius *
                  ((s.position - geo.pin_centre(s.pin)) /
                   s.position.distance(geo.pin_centre(s.pin)));
              double      best = 1e300, t_best = 0;
              const Edge *edge = nullptr;
              for (const Edge &e : edges[s.pin])
                {
                  const dealii::Tensor<1, 2> ab = e.b - e.a;
                  const double               t =
                    std::clamp((P - e.a) * ab / ab.norm_square(), 0., 1.);
                  const double d = P.distance(e.a + t * ab);
                  if (d < best)
                    {
                      best   = d;
                      t_best = t;
                      edge   = &e;
                    }
                }
              AssertThrow(edge != nullptr,
                          dealii::ExcMessage("quasi-static: pin " +
                                             std::to_string(s.pin) +
                                             " has no surface edges."));
              s.master_weights = {1. - t_best, t_best};
              s.master_dofs[0] = {edge->dofs[0], edge->dofs[2]};
              s.master_dofs[1] = {edge->dofs[1], edge->dofs[3]};
              masters.insert(masters.end(),
                             edge->dofs.begin(),
                             edge->dofs.end());
            }
          slaves.push_back(s);
        }
      problem->set_extra_relevant_dofs(masters);
    }



    void
    QuasiStatic2D::solve_with_active_set(
      const bool                             with_gaps,
      const double                           beta,
      dealii::TrilinosWrappers::MPI::Vector &u)
    {
      const dealii::Point<2> centre = geo.disc_centre(0, psi);
      problem->setup_system([&](dealii::AffineConstraints<double> &c) {
        // Rigid pins are held in place; elastic pins at their core.
        const bool rigid =
          prm.scene.pins == parameters::SceneParameters::PinModel::rigid;
        for (const auto d : (rigid ? pin_dofs : core_dofs))
          if (c.can_store_line(d) && !c.is_constrained(d))
            c.add_line(d);
        // Load: the crank holes turn rigidly by beta about the disc centre.
        for (const auto &cell : problem->dof_handler().active_cell_iterators())
          {
            if (cell->is_artificial() || cell->material_id() != ids::disc(0))
              continue;
            for (const unsigned int v : cell->vertex_indices())
              for (unsigned int comp = 0; comp < 2; ++comp)
                {
                  const auto d = cell->vertex_dof_index(v, comp);
                  if (!crank_hole_dofs.count(d) || !c.can_store_line(d) ||
                      c.is_constrained(d))
                    continue;
                  const dealii::Tensor<1, 2> r = cell->vertex(v) - centre;
                  c.add_line(d);
                  c.set_inhomogeneity(d, beta * (comp == 0 ? -r[1] : r[0]));
                }
          }
        // Active contact nodes: n . u = -gap0, eliminating the dominant
        // component (the matrix stays SPD).
        for (const unsigned int i : active)
          {
            const SlaveNode   &s = slaves[i];
            const unsigned int k =
              std::abs(s.normal[0]) >= std::abs(s.normal[1]) ? 0 : 1;
            const auto dk = s.dofs[k], dother = s.dofs[1 - k];
            if (!c.can_store_line(dk) || c.is_constrained(dk))
              continue;
            c.add_line(dk);
            c.add_entry(dk, dother, -s.normal[1 - k] / s.normal[k]);
            // Elastic pin: + n . u_pin(P) / n_k.
            for (unsigned int comp = 0; comp < 2; ++comp)
              for (unsigned int a = 0; a < s.master_weights.size(); ++a)
                c.add_entry(dk,
                            s.master_dofs[comp][a],
                            s.normal[comp] * s.master_weights[a] / s.normal[k]);
            c.set_inhomogeneity(dk, with_gaps ? -s.gap0 / s.normal[k] : 0.);
          }
      });
      problem->assemble({});
      last_iterations += problem->solve(
        prm.contact.linear_solver == "direct" ?
          elasticity::LinearElasticity<2>::Solver::direct :
        prm.contact.linear_solver == "cg-amg-translations" ?
          elasticity::LinearElasticity<2>::Solver::cg_amg_translations_only :
          elasticity::LinearElasticity<2>::Solver::cg_amg,
        prm.contact.solver_tolerance);
      u = problem->solution();
    }



    double
    QuasiStatic2D::reaction_torque(
      const dealii::TrilinosWrappers::MPI::Vector &f) const
    {
      // Torque about the disc centre of the reactions at the load surface,
      // per unit thickness [N mm / mm].
      const dealii::Point<2> centre = geo.disc_centre(0, psi);
      double                 torque = 0;
      std::set<unsigned int> done;
      for (const auto &cell : problem->dof_handler().active_cell_iterators())
        {
          if (!cell->is_locally_owned() || cell->material_id() != ids::disc(0))
            continue;
          for (const unsigned int v : cell->vertex_indices())
            {
              const auto dx = cell->vertex_dof_index(v, 0);
              const auto dy = cell->vertex_dof_index(v, 1);
              if (!crank_hole_dofs.count(dx) ||
                  !problem->locally_owned_dofs().is_element(dx) ||
                  !done.insert(cell->vertex_index(v)).second)
                continue;
              const dealii::Tensor<1, 2> r = cell->vertex(v) - centre;
              torque += r[0] * f[dy] - r[1] * f[dx];
            }
        }
      return dealii::Utilities::MPI::sum(torque, comm);
    }



    void
    QuasiStatic2D::solve(const double                           torque,
                         postprocess::StiffnessRow             &row,
                         std::vector<postprocess::PinForceRow> &pins)
    {
      const auto   start = std::chrono::steady_clock::now();
      const double b     = prm.geometry.tooth_width;
      // Target torque per unit thickness [N mm / mm].
      const double           target = torque * 1e3 / b;
      const dealii::Point<2> centre = geo.disc_centre(0, psi);

      // Without a previous state, start from the nodes that the analytical
      // model's rotation would push into the pins: with no active node the
      // disc turns freely and the torque cannot fix beta.
      if (active.empty())
        {
          const analytic::StageModel model(prm);
          const double beta_a = model.solve(psi, torque, 0.).rotation;
          for (unsigned int i = 0; i < slaves.size(); ++i)
            {
              const dealii::Tensor<1, 2> r = slaves[i].position - centre;
              // The rigid rotation moves the node by beta z x r.
              const double n_dot_u = beta_a * (slaves[i].normal[1] * r[0] -
                                               slaves[i].normal[0] * r[1]);
              if (slaves[i].gap0 + n_dot_u < 0)
                active.insert(i);
            }
        }

      dealii::TrilinosWrappers::MPI::Vector u0, u1;
      dealii::TrilinosWrappers::MPI::Vector f0, f1;
      double                                beta = 0, t1 = 0;
      std::vector<std::set<unsigned int>>   history;
      unsigned int                          it = 0;
      last_iterations                          = 0;
      for (;; ++it)
        {
          AssertThrow(it < prm.contact.max_active_set_iterations,
                      dealii::ExcMessage(
                        "quasi-static: the active set did not settle in " +
                        std::to_string(prm.contact.max_active_set_iterations) +
                        " iterations (Contact/Maximum active set iterations; "
                        "torque " +
                        std::to_string(torque) + " N m)."));
          solve_with_active_set(true, 0., u0);
          f0 = problem->internal_forces(u0);
          solve_with_active_set(false, 1., u1);
          f1              = problem->internal_forces(u1);
          const double t0 = reaction_torque(f0);
          t1              = reaction_torque(f1);
          beta            = (target - t0) / t1;

          // New active set from the gaps and the multipliers of the owned
          // slave nodes, then merged over the ranks.
          std::vector<unsigned int> mine;
          for (unsigned int i = 0; i < slaves.size(); ++i)
            {
              const SlaveNode &s = slaves[i];
              if (!problem->locally_owned_dofs().is_element(s.dofs[0]))
                continue;
              double gap = s.gap0, lambda = 0;
              for (unsigned int c = 0; c < 2; ++c)
                {
                  gap += s.normal[c] * (u0[s.dofs[c]] + beta * u1[s.dofs[c]]);
                  for (unsigned int a = 0; a < s.master_weights.size(); ++a)
                    gap -= s.normal[c] * s.master_weights[a] *
                           (u0[s.master_dofs[c][a]] +
                            beta * u1[s.master_dofs[c][a]]);
                  lambda +=
                    s.normal[c] * (f0[s.dofs[c]] + beta * f1[s.dofs[c]]);
                }
              const bool was_active = active.count(i);
              // lambda + c (-gap) > 0: for an active node gap = 0, for an
              // inactive one lambda = 0; c only needs the right sign here.
              if ((was_active && lambda > 0) || (!was_active && gap < 0))
                mine.push_back(i);
            }
          std::set<unsigned int> next;
          for (const auto &part :
               dealii::Utilities::MPI::all_gather(comm, mine))
            next.insert(part.begin(), part.end());
          if (std::getenv("CYCLOID_DEBUG"))
            {
              std::cerr << "it " << it << " beta " << beta << " T0 " << t0
                        << " T1 " << t1 << " active " << active.size()
                        << " next " << next.size() << " :";
              for (const auto i : next)
                if (!active.count(i))
                  std::cerr << " +" << i << "(pin " << slaves[i].pin << ")";
              for (const auto i : active)
                if (!next.count(i))
                  std::cerr << " -" << i << "(pin " << slaves[i].pin << ")";
              std::cerr << std::endl;
            }
          if (next == active)
            break;
          AssertThrow(std::find(history.begin(), history.end(), next) ==
                        history.end(),
                      dealii::ExcMessage(
                        "quasi-static: the active set cycles (a set seen "
                        "before returned at iteration " +
                        std::to_string(it) + ", torque " +
                        std::to_string(torque) + " N m)."));
          history.push_back(active);
          active = next;
        }

      {
        dealii::TrilinosWrappers::MPI::Vector a(problem->locally_owned_dofs(),
                                                comm),
          b(problem->locally_owned_dofs(), comm);
        a = u0;
        b = u1;
        a.add(beta, b);
        u_last.reinit(problem->locally_owned_dofs(),
                      problem->locally_relevant_dofs(),
                      comm);
        u_last = a;
        a      = f0;
        b      = f1;
        a.add(beta, b);
        f_last.reinit(problem->locally_owned_dofs(),
                      problem->locally_relevant_dofs(),
                      comm);
        f_last = a;
      }

      // Pin forces from the slave reactions (force of the pin on the disc),
      // scaled to the tooth width.
      const unsigned int  zp = prm.geometry.n_pins;
      std::vector<double> fx(zp, 0.), fy(zp, 0.), moment(zp, 0.);
      for (const unsigned int i : active)
        {
          const SlaveNode &s = slaves[i];
          if (!problem->locally_owned_dofs().is_element(s.dofs[0]))
            continue;
          const double               gx = f0[s.dofs[0]] + beta * f1[s.dofs[0]];
          const double               gy = f0[s.dofs[1]] + beta * f1[s.dofs[1]];
          const dealii::Tensor<1, 2> r  = s.position - centre;
          fx[s.pin] += gx * b;
          fy[s.pin] += gy * b;
          moment[s.pin] += (r[0] * gy - r[1] * gx) * b;
        }
      dealii::Utilities::MPI::sum(fx, comm, fx);
      dealii::Utilities::MPI::sum(fy, comm, fy);
      dealii::Utilities::MPI::sum(moment, comm, moment);

      row.torque_Nm          = torque;
      row.rotation_rad       = beta;
      row.k_tangent          = t1 * b * 1e-3;
      row.k_secant           = torque / beta;
      row.iterations         = it + 1;
      row.dofs               = problem->n_dofs();
      row.reaction_torque_Nm = 0;
      row.pins_in_contact    = 0;
      row.max_pin_force_N    = 0;
      pins.clear();
      const auto contacts = geo.pin_contacts(0, psi);
      // Rigid take-up (lost motion) of the exact geometry, as in the
      // analytical model: the rotation that closes the first clearance.
      double takeup = std::numeric_limits<double>::max();
      for (const auto &c : contacts)
        if ((torque >= 0 ? c.arm : -c.arm) > 1e-9)
          takeup =
            std::min(takeup, std::max(c.clearance, 0.) / std::abs(c.arm));
      row.takeup_rad       = (torque >= 0 ? 1. : -1.) * takeup;
      row.k_secant_elastic = torque / (beta - row.takeup_rad);
      for (unsigned int j = 0; j < zp; ++j)
        {
          postprocess::PinForceRow p;
          p.disc = 0;
          p.pin  = j;
          p.fx_N = fx[j] + 0.;
          p.fy_N = fy[j] + 0.;
          p.fn_N = std::hypot(fx[j], fy[j]);
          // Moment of the pin's force about the disc centre resists a
          // positive torque: arm = -(r x F)/|F| with F on the disc.
          p.arm_mm       = p.fn_N > 0 ? -moment[j] / p.fn_N : contacts[j].arm;
          p.clearance_um = contacts[j].clearance * 1e3;
          p.phase_deg    = contacts[j].phase * 180. / dealii::numbers::PI;
          p.contact_x_mm = contacts[j].contact_point[0];
          p.contact_y_mm = contacts[j].contact_point[1];
          // Contact half-width: half the arc between the outermost active
          // nodes of this pin, plus half a node spacing on each side.
          {
            double                 lo = 1e300, hi = -1e300, spacing = 1e300;
            const dealii::Point<2> c = geo.pin_centre(j);
            const double a0 = std::atan2(contacts[j].contact_point[1] - c[1],
                                         contacts[j].contact_point[0] - c[0]);
            std::vector<double> angles;
            for (const SlaveNode &s : slaves)
              if (s.pin == j)
                {
                  double a =
                    std::atan2(s.position[1] - c[1], s.position[0] - c[0]) - a0;
                  a = std::remainder(a, 2. * dealii::numbers::PI);
                  angles.push_back(a);
                }
            for (const unsigned int i : active)
              if (slaves[i].pin == j)
                {
                  double a = std::atan2(slaves[i].position[1] - c[1],
                                        slaves[i].position[0] - c[0]) -
                             a0;
                  a  = std::remainder(a, 2. * dealii::numbers::PI);
                  lo = std::min(lo, a);
                  hi = std::max(hi, a);
                }
            if (hi >= lo)
              {
                for (const double a : angles)
                  if (a > hi || a < lo)
                    spacing =
                      std::min(spacing,
                               std::min(std::abs(a - hi), std::abs(a - lo)));
                if (spacing > 1e200)
                  spacing = 0;
                p.contact_halfwidth_um = 1e3 * prm.geometry.pin_radius *
                                         (0.5 * (hi - lo) + 0.5 * spacing);
              }
            p.hertz_halfwidth_um =
              1e3 *
              analytic::hertz_half_width(
                p.fn_N,
                b,
                prm.geometry.pin_radius,
                contacts[j].curvature_radius,
                prm.material.disc.plane_strain_modulus(),
                prm.scene.pins == parameters::SceneParameters::PinModel::rigid ?
                  0. :
                  prm.material.pin.plane_strain_modulus());
          }
          row.reaction_torque_Nm += p.fn_N * p.arm_mm * 1e-3;
          if (p.fn_N > 0)
            ++row.pins_in_contact;
          row.max_pin_force_N = std::max(row.max_pin_force_N, p.fn_N);
          pins.push_back(p);
        }
      row.wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
    }
  } // namespace contact
} // namespace cycloid



namespace cycloid
{
  namespace contact
  {
    namespace
    {
      /** Von Mises stress of the displacement field, per body material
       * (plane strain: sigma_zz = lambda tr(eps)). */
      class VonMises : public dealii::DataPostprocessorScalar<2>
      {
      public:
        explicit VonMises(const parameters::AllParameters &prm)
          : dealii::DataPostprocessorScalar<2>("von_Mises",
                                               dealii::update_gradients)
          , prm(prm)
        {}

        void
        evaluate_vector_field(
          const dealii::DataPostprocessorInputs::Vector<2> &inputs,
          std::vector<dealii::Vector<double>> &computed) const override
        {
          const auto   cell = inputs.template get_cell<2>();
          const auto  &m    = mesh::ids::is_pin(cell->material_id()) ?
                                prm.material.pin :
                                prm.material.disc;
          const double E = m.youngs_modulus, nu = m.poissons_ratio;
          const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
          const double mu     = E / (2 * (1 + nu));
          for (unsigned int q = 0; q < computed.size(); ++q)
            {
              const auto  &g   = inputs.solution_gradients[q];
              const double e00 = g[0][0], e11 = g[1][1],
                           e01 = 0.5 * (g[0][1] + g[1][0]);
              const double tr  = e00 + e11;
              const double s00 = lambda * tr + 2 * mu * e00;
              const double s11 = lambda * tr + 2 * mu * e11;
              const double s22 = lambda * tr;
              const double s01 = 2 * mu * e01;
              computed[q](0)   = std::sqrt(0.5 * ((s00 - s11) * (s00 - s11) +
                                                (s11 - s22) * (s11 - s22) +
                                                (s22 - s00) * (s22 - s00)) +
                                         3 * s01 * s01);
            }
        }

      private:
        const parameters::AllParameters &prm;
      };
    } // namespace



    void
    QuasiStatic2D::output_results(const unsigned int step)
    {
      // Nodal fields of the contact: the reaction at active slave nodes
      // (force per unit thickness, N/mm) and the active flag.
      dealii::TrilinosWrappers::MPI::Vector force(problem->locally_owned_dofs(),
                                                  comm),
        flag(problem->locally_owned_dofs(), comm);
      for (const unsigned int i : active)
        for (unsigned int c = 0; c < 2; ++c)
          if (problem->locally_owned_dofs().is_element(slaves[i].dofs[c]))
            {
              force[slaves[i].dofs[c]] = f_last[slaves[i].dofs[c]];
              flag[slaves[i].dofs[c]]  = 1.;
            }
      force.compress(dealii::VectorOperation::insert);
      flag.compress(dealii::VectorOperation::insert);
      dealii::TrilinosWrappers::MPI::Vector force_g(
        problem->locally_owned_dofs(), problem->locally_relevant_dofs(), comm),
        flag_g(problem->locally_owned_dofs(),
               problem->locally_relevant_dofs(),
               comm);
      force_g = force;
      flag_g  = flag;

      dealii::DataOut<2> data_out;
      data_out.attach_dof_handler(problem->dof_handler());
      const std::vector<
        dealii::DataComponentInterpretation::DataComponentInterpretation>
        vector(
          2, dealii::DataComponentInterpretation::component_is_part_of_vector);
      data_out.add_data_vector(u_last,
                               std::vector<std::string>(2, "displacement"),
                               dealii::DataOut<2>::type_dof_data,
                               vector);
      data_out.add_data_vector(force_g,
                               std::vector<std::string>(2, "contact_force"),
                               dealii::DataOut<2>::type_dof_data,
                               vector);
      data_out.add_data_vector(flag_g,
                               std::vector<std::string>(2, "active_set"),
                               dealii::DataOut<2>::type_dof_data,
                               vector);
      const VonMises von_mises(prm);
      data_out.add_data_vector(u_last, von_mises);
      dealii::Vector<float> body(tria.n_active_cells()),
        rank(tria.n_active_cells());
      for (const auto &cell : tria.active_cell_iterators())
        {
          body(cell->active_cell_index()) = cell->material_id();
          rank(cell->active_cell_index()) = cell->subdomain_id();
        }
      data_out.add_data_vector(body, "body_id");
      data_out.add_data_vector(rank, "mpi_rank");
      data_out.build_patches(problem->mapping(), 1);

      const std::string  number = dealii::Utilities::int_to_string(step, 4);
      const std::string  name   = "solution-" + number;
      const unsigned int r = dealii::Utilities::MPI::this_mpi_process(comm);
      {
        std::ofstream out(prm.run.output_directory + "/" + name + "." +
                          dealii::Utilities::int_to_string(r, 4) + ".vtu");
        data_out.write_vtu(out);
      }
      if (r == 0)
        {
          std::vector<std::string> pieces;
          for (unsigned int k = 0;
               k < dealii::Utilities::MPI::n_mpi_processes(comm);
               ++k)
            pieces.push_back(name + "." +
                             dealii::Utilities::int_to_string(k, 4) + ".vtu");
          std::ofstream pvtu(prm.run.output_directory + "/" + name + ".pvtu");
          data_out.write_pvtu_record(pvtu, pieces);
          written.emplace_back(step, name + ".pvtu");
          std::ofstream pvd(prm.run.output_directory + "/solution.pvd");
          dealii::DataOutBase::write_pvd_record(pvd, written);
        }
    }
  } // namespace contact
} // namespace cycloid

#include <deal.II/base/exceptions.h>

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <cycloid/contact/contact_problem.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <tuple>

namespace cycloid
{
  namespace contact
  {
    namespace
    {
      /** Distance in the xy plane. */
      template <int dim>
      double
      planar_distance(const dealii::Point<dim> &x, const dealii::Point<2> &c)
      {
        return std::hypot(x[0] - c[0], x[1] - c[1]);
      }

      /** The cylinder nearest to @p x (in the xy plane) and the distance
       * to its axis. */
      template <int dim>
      std::pair<unsigned int, double>
      nearest_cylinder(const std::vector<MasterCylinder> &cylinders,
                       const dealii::Point<dim>          &x)
      {
        unsigned int nearest = 0;
        double       d       = std::numeric_limits<double>::max();
        for (unsigned int j = 0; j < cylinders.size(); ++j)
          if (planar_distance(x, cylinders[j].centre) < d)
            {
              d       = planar_distance(x, cylinders[j].centre);
              nearest = j;
            }
        return {nearest, d};
      }
    } // namespace



    template <int dim>
    ContactProblem<dim>::ContactProblem(
      const dealii::parallel::TriangulationBase<dim> &triangulation,
      const unsigned int                              degree,
      const std::map<dealii::types::material_id, parameters::ElasticMaterial>
                            &materials,
      const ContactSettings &settings)
      : comm(triangulation.get_communicator())
      , settings(settings)
      , materials(materials)
      , problem(
          std::make_unique<elasticity::LinearElasticity<dim>>(triangulation,
                                                              degree,
                                                              materials))
    {}



    template <int dim>
    void
    ContactProblem<dim>::set_contact(
      const std::set<dealii::types::material_id> &bodies,
      const dealii::types::boundary_id            surface,
      const std::vector<MasterCylinder>          &masters,
      const bool                                  deformable)
    {
      slave_bodies       = bodies;
      slave_surface      = surface;
      cylinders          = masters;
      deformable_masters = deformable;
    }



    template <int dim>
    void
    ContactProblem<dim>::set_ties(const dealii::types::material_id body,
                                  const dealii::types::boundary_id surface)
    {
      with_ties    = true;
      tied_body    = body;
      tied_surface = surface;
    }



    template <int dim>
    void
    ContactProblem<dim>::setup()
    {
      problem->set_extra_relevant_dofs({});
      problem->distribute_dofs();
      collect_master_faces();
      find_slave_nodes();
      find_tied_nodes();
      ghost_master_dofs();
      active.clear();
      fixed.clear();
      load.clear();
      reset_slave_results();
    }



    template <int dim>
    void
    ContactProblem<dim>::reset_slave_results()
    {
      reactions.assign(slaves.size(), dealii::Tensor<1, dim>());
      gaps.resize(slaves.size());
      for (unsigned int i = 0; i < slaves.size(); ++i)
        gaps[i] = slaves[i].gap0;
    }



    template <int dim>
    void
    ContactProblem<dim>::ghost_master_dofs()
    {
      // Every rank needs the master DoFs of all constraints it stores.
      std::vector<dealii::types::global_dof_index> extra;
      for (const auto &s : slaves)
        extra.insert(extra.end(), s.master_dofs.begin(), s.master_dofs.end());
      for (const auto &t : ties)
        for (unsigned int c = 0; c < dim; ++c)
          extra.insert(extra.end(), t.masters[c].begin(), t.masters[c].end());
      problem->set_extra_relevant_dofs(extra);
    }



    template <int dim>
    void
    ContactProblem<dim>::collect_master_faces()
    {
      master_faces.assign(cylinders.size(), {});
      master_boxes.assign(cylinders.size(), {});
      if (!deformable_masters && !with_ties)
        return;
      std::map<dealii::types::material_id, unsigned int> by_body;
      for (unsigned int j = 0; j < cylinders.size(); ++j)
        by_body[cylinders[j].body] = j;
      // A shared triangulation without artificial cells: every rank sees
      // every cell and its DoF indices.
      for (const auto &cell : problem->dof_handler().active_cell_iterators())
        {
          const auto it = by_body.find(cell->material_id());
          if (it == by_body.end())
            continue;
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == cylinders[it->second].surface)
              {
                master_faces[it->second].emplace_back(cell, f);
                // (centre angle, half angular width, z min, z max)
                const auto  &c  = cylinders[it->second].centre;
                const auto   x0 = cell->face(f)->center();
                const double a0 = std::atan2(x0[1] - c[1], x0[0] - c[0]);
                std::array<double, 4> box{{a0, 0., 1e300, -1e300}};
                for (const unsigned int v : cell->face(f)->vertex_indices())
                  {
                    const auto x = cell->face(f)->vertex(v);
                    box[1] =
                      std::max(box[1],
                               std::abs(std::remainder(
                                 std::atan2(x[1] - c[1], x[0] - c[0]) - a0,
                                 2. * dealii::numbers::PI)));
                    box[2] = std::min(box[2], x[dim - 1]);
                    box[3] = std::max(box[3], x[dim - 1]);
                  }
                master_boxes[it->second].push_back(box);
              }
        }
    }



    template <int dim>
    bool
    ContactProblem<dim>::master_weights(
      const unsigned int                                             j,
      const dealii::Point<dim>                                      &P,
      std::array<std::vector<dealii::types::global_dof_index>, dim> &dofs,
      std::array<std::vector<double>, dim> &weights) const
    {
      const auto &fe = problem->finite_element();
      // Unit coordinates of P on a face from the (angle, z) coordinates of
      // its vertices on the cylinder: the manifold places refined vertices
      // and the mapping's support points uniformly in angle and z, so the
      // bilinear (linear in 2D) interpolation of (angle, z) is exact.
      const MasterCylinder &m = cylinders[j];
      const double theta = std::atan2(P[1] - m.centre[1], P[0] - m.centre[0]);
      constexpr unsigned int n_face_vertices = 1u << (dim - 1);
      for (unsigned int k = 0; k < master_faces[j].size(); ++k)
        {
          // Quick rejection by the face's (angle, z) box.
          const auto &box = master_boxes[j][k];
          if (std::abs(
                std::remainder(theta - box[0], 2. * dealii::numbers::PI)) >
                box[1] + 1e-9 ||
              (dim == 3 &&
               (P[dim - 1] < box[2] - 1e-9 || P[dim - 1] > box[3] + 1e-9)))
            continue;
          const auto &[cell, f] = master_faces[j][k];
          std::array<unsigned int, dim - 1> axes;
          for (unsigned int a = 0, n = 0; a < dim; ++a)
            if (a != f / 2)
              axes[n++] = a;
          std::array<std::array<double, 2>, n_face_vertices>       rel;
          std::array<std::array<double, dim - 1>, n_face_vertices> corner;
          for (unsigned int v = 0; v < n_face_vertices; ++v)
            {
              const unsigned int cv =
                dealii::GeometryInfo<dim>::face_to_cell_vertices(f, v);
              const auto x = cell->vertex(cv);
              rel[v][0] =
                m.radius * std::remainder(std::atan2(x[1] - m.centre[1],
                                                     x[0] - m.centre[0]) -
                                            theta,
                                          2. * dealii::numbers::PI);
              rel[v][1]    = dim == 3 ? x[dim - 1] - P[dim - 1] : 0.;
              const auto u = dealii::GeometryInfo<dim>::unit_cell_vertex(cv);
              for (unsigned int a = 0; a < dim - 1; ++a)
                corner[v][a] = u[axes[a]];
            }
          // Newton on sum_v N_v(xi) rel_v = 0 (N bilinear in xi).
          std::array<double, dim - 1> xi;
          xi.fill(0.5);
          for (unsigned int newton = 0; newton < 20; ++newton)
            {
              double r[2] = {0, 0}, J[2][2] = {{0, 0}, {0, 0}};
              for (unsigned int v = 0; v < n_face_vertices; ++v)
                {
                  double N = 1, dN[2] = {1, 1};
                  for (unsigned int a = 0; a < dim - 1; ++a)
                    {
                      const double l  = corner[v][a] > 0.5 ? xi[a] : 1 - xi[a];
                      const double dl = corner[v][a] > 0.5 ? 1. : -1.;
                      N *= l;
                      for (unsigned int b = 0; b < dim - 1; ++b)
                        dN[b] *= (a == b ? dl : l);
                    }
                  for (unsigned int c = 0; c < dim - 1; ++c)
                    {
                      r[c] += N * rel[v][c];
                      for (unsigned int b = 0; b < dim - 1; ++b)
                        J[c][b] += dN[b] * rel[v][c];
                    }
                }
              if (dim == 2)
                xi[0] -= r[0] / J[0][0];
              else
                {
                  const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
                  xi[0] -= (J[1][1] * r[0] - J[0][1] * r[1]) / det;
                  xi[dim - 2] -= (-J[1][0] * r[0] + J[0][0] * r[1]) / det;
                }
            }
          bool inside = true;
          for (unsigned int a = 0; a < dim - 1; ++a)
            inside &= std::isfinite(xi[a]) && xi[a] > -1e-6 && xi[a] < 1 + 1e-6;
          if (!inside)
            continue;
          dealii::Point<dim> unit;
          unit[f / 2] = f % 2;
          for (unsigned int a = 0; a < dim - 1; ++a)
            unit[axes[a]] = std::clamp(xi[a], 0., 1.);
          std::vector<dealii::types::global_dof_index> indices(
            fe.n_dofs_per_cell());
          cell->get_dof_indices(indices);
          for (auto &d : dofs)
            d.clear();
          for (auto &w : weights)
            w.clear();
          for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
            {
              const unsigned int c     = fe.system_to_component_index(i).first;
              const double       value = fe.shape_value_component(i, unit, c);
              if (std::abs(value) > 1e-12)
                {
                  dofs[c].push_back(indices[i]);
                  weights[c].push_back(value);
                }
            }
          return true;
        }
      return false;
    }



    template <int dim>
    void
    ContactProblem<dim>::find_slave_nodes()
    {
      slaves.clear();
      const auto &fe      = problem->finite_element();
      const auto &mapping = problem->mapping();
      const auto &hanging = problem->hanging_node_constraints();
      const dealii::QGauss<dim - 1> quadrature(fe.degree + 1);
      dealii::FEFaceValues<dim>     fe_face(mapping,
                                        fe,
                                        quadrature,
                                        dealii::update_values |
                                          dealii::update_JxW_values);
      const auto &unit_points = fe.base_element(0).get_unit_support_points();
      std::map<dealii::types::global_dof_index, unsigned int> index_of;
      std::vector<dealii::types::global_dof_index>            indices(
        fe.n_dofs_per_cell());
      for (const auto &cell : problem->dof_handler().active_cell_iterators())
        {
          if (!slave_bodies.count(cell->material_id()))
            continue;
          for (const unsigned int f : cell->face_indices())
            {
              if (!cell->face(f)->at_boundary() ||
                  cell->face(f)->boundary_id() != slave_surface)
                continue;
              cell->get_dof_indices(indices);
              fe_face.reinit(cell, f);
              for (unsigned int k = 0; k < fe.n_dofs_per_face(f); ++k)
                {
                  const unsigned int i = fe.face_to_cell_index(k, f);
                  const auto [component, node] =
                    fe.system_to_component_index(i);
                  if (component != 0)
                    continue;
                  double w = 0;
                  for (const unsigned int q :
                       fe_face.quadrature_point_indices())
                    w += fe_face.shape_value(i, q) * fe_face.JxW(q);
                  const auto known = index_of.find(indices[i]);
                  if (known != index_of.end())
                    {
                      if (known->second !=
                          dealii::numbers::invalid_unsigned_int)
                        slaves[known->second].weight += w;
                      continue;
                    }
                  dealii::Point<dim> x =
                    mapping.transform_unit_to_real_cell(cell,
                                                        unit_points[node]);
                  if (placement)
                    x = placement(cell->material_id(), x);
                  const auto [nearest, d] = nearest_cylinder(cylinders, x);
                  const double gap        = d - cylinders[nearest].radius;
                  if (gap > settings.search_distance)
                    {
                      index_of[indices[i]] =
                        dealii::numbers::invalid_unsigned_int;
                      continue;
                    }
                  SlaveNode<dim> s;
                  s.body     = cell->material_id();
                  s.cylinder = nearest;
                  s.position = x;
                  for (unsigned int c = 0; c < 2; ++c)
                    s.normal[c] = (x[c] - cylinders[nearest].centre[c]) / d;
                  s.gap0   = gap;
                  s.weight = w;
                  for (unsigned int c = 0; c < dim; ++c)
                    s.dofs[c] = indices[fe.component_to_system_index(c, node)];
                  s.hanging            = hanging.is_constrained(s.dofs[0]);
                  index_of[indices[i]] = slaves.size();
                  slaves.push_back(s);
                }
            }
        }
      if (settings.formulation == Formulation::mortar)
        {
          weight_by_dual_basis();
          return;
        }
      if (!deformable_masters)
        return;
      for (auto &s : slaves)
        {
          if (s.hanging)
            continue;
          const MasterCylinder &m = cylinders[s.cylinder];
          dealii::Point<dim>    P = s.position;
          for (unsigned int c = 0; c < 2; ++c)
            P[c] = m.centre[c] + m.radius * s.normal[c];
          std::array<std::vector<dealii::types::global_dof_index>, dim> dofs;
          std::array<std::vector<double>, dim>                          w;
          AssertThrow(master_weights(s.cylinder, P, dofs, w),
                      dealii::ExcMessage(
                        "contact: no face of master body " +
                        std::to_string(m.body) +
                        " holds the projection of a "
                        "slave node; is the master surface meshed?"));
          for (unsigned int c = 0; c < 2; ++c)
            for (unsigned int a = 0; a < dofs[c].size(); ++a)
              {
                s.master_dofs.push_back(dofs[c][a]);
                s.master_coefficients.push_back(s.normal[c] * w[c][a]);
              }
        }
    }



    template <int dim>
    void
    ContactProblem<dim>::weight_by_dual_basis()
    {
      const auto &fe      = problem->finite_element();
      const auto &mapping = problem->mapping();
      // More points than the slave polynomials need: the master field is
      // only piecewise smooth along the slave face.
      const dealii::QGauss<dim - 1> quadrature(fe.degree + 4);
      dealii::FEFaceValues<dim>     fe_face(mapping,
                                        fe,
                                        quadrature,
                                        dealii::update_values |
                                          dealii::update_quadrature_points |
                                          dealii::update_JxW_values);
      std::map<dealii::types::global_dof_index, unsigned int> index_of;
      for (unsigned int i = 0; i < slaves.size(); ++i)
        index_of[slaves[i].dofs[0]] = i;
      std::vector<dealii::Tensor<1, dim>> normals(slaves.size());
      std::vector<std::map<dealii::types::global_dof_index, double>> coef(
        slaves.size());
      std::vector<dealii::types::global_dof_index> indices(
        fe.n_dofs_per_cell());
      for (const auto &cell : problem->dof_handler().active_cell_iterators())
        {
          if (!slave_bodies.count(cell->material_id()))
            continue;
          for (const unsigned int f : cell->face_indices())
            {
              if (!cell->face(f)->at_boundary() ||
                  cell->face(f)->boundary_id() != slave_surface)
                continue;
              cell->get_dof_indices(indices);
              // The face's nodes (x components) and their slave indices.
              std::vector<unsigned int> local, slave;
              for (unsigned int k = 0; k < fe.n_dofs_per_face(f); ++k)
                {
                  const unsigned int i = fe.face_to_cell_index(k, f);
                  if (fe.system_to_component_index(i).first != 0)
                    continue;
                  local.push_back(i);
                  const auto it = index_of.find(indices[i]);
                  slave.push_back(it == index_of.end() ?
                                    dealii::numbers::invalid_unsigned_int :
                                    it->second);
                }
              if (std::all_of(
                    slave.begin(), slave.end(), [](const unsigned int s) {
                      return s == dealii::numbers::invalid_unsigned_int;
                    }))
                continue;
              fe_face.reinit(cell, f);
              // Dual basis psi_a = sum_b A_ab phi_b with A = D M^-1
              // (biorthogonal: int psi_a phi_b = delta_ab int phi_a).
              const unsigned int         n = local.size();
              dealii::FullMatrix<double> M(n, n), Minv(n, n);
              dealii::Vector<double>     D(n);
              for (const unsigned int q : fe_face.quadrature_point_indices())
                for (unsigned int a = 0; a < n; ++a)
                  {
                    const double pa = fe_face.shape_value(local[a], q);
                    D(a) += pa * fe_face.JxW(q);
                    for (unsigned int b = 0; b < n; ++b)
                      M(a, b) +=
                        pa * fe_face.shape_value(local[b], q) * fe_face.JxW(q);
                  }
              Minv.invert(M);
              for (const unsigned int q : fe_face.quadrature_point_indices())
                {
                  dealii::Point<dim> x = fe_face.quadrature_point(q);
                  if (placement)
                    x = placement(cell->material_id(), x);
                  // Per cylinder met on this face: gap, normal, master weights.
                  std::map<
                    unsigned int,
                    std::tuple<
                      dealii::Tensor<1, 2>,
                      std::array<std::vector<dealii::types::global_dof_index>,
                                 dim>,
                      std::array<std::vector<double>, dim>>>
                    at;
                  for (unsigned int a = 0; a < n; ++a)
                    {
                      if (slave[a] == dealii::numbers::invalid_unsigned_int)
                        continue;
                      SlaveNode<dim> &s = slaves[slave[a]];
                      if (s.hanging)
                        continue;
                      auto it = at.find(s.cylinder);
                      if (it == at.end())
                        {
                          const MasterCylinder &m = cylinders[s.cylinder];
                          const double         d = planar_distance(x, m.centre);
                          dealii::Tensor<1, 2> normal;
                          normal[0] = (x[0] - m.centre[0]) / d;
                          normal[1] = (x[1] - m.centre[1]) / d;
                          std::array<
                            std::vector<dealii::types::global_dof_index>,
                            dim>
                                                               mdofs;
                          std::array<std::vector<double>, dim> mw;
                          if (deformable_masters)
                            {
                              dealii::Point<dim> P = x;
                              for (unsigned int c = 0; c < 2; ++c)
                                P[c] = m.centre[c] + m.radius * normal[c];
                              AssertThrow(
                                master_weights(s.cylinder, P, mdofs, mw),
                                dealii::ExcMessage(
                                  "contact: no face of master body " +
                                  std::to_string(m.body) +
                                  " holds the projection of a slave "
                                  "quadrature point."));
                            }
                          it = at.emplace(s.cylinder,
                                          std::make_tuple(normal, mdofs, mw))
                                 .first;
                        }
                      const auto &[normal, mdofs, mw] = it->second;
                      double psi                      = 0;
                      for (unsigned int b = 0; b < n; ++b)
                        psi +=
                          D(a) * Minv(a, b) * fe_face.shape_value(local[b], q);
                      const double w = psi * fe_face.JxW(q);
                      for (unsigned int c = 0; c < 2; ++c)
                        normals[slave[a]][c] += w * normal[c];
                      for (unsigned int c = 0; c < 2; ++c)
                        for (unsigned int k = 0; k < mdofs[c].size(); ++k)
                          coef[slave[a]][mdofs[c][k]] +=
                            w * normal[c] * mw[c][k];
                    }
                }
            }
        }
      for (unsigned int i = 0; i < slaves.size(); ++i)
        {
          SlaveNode<dim> &s = slaves[i];
          if (s.hanging || s.weight <= 0)
            continue;
          // The initial gap stays collocated at the node (see
          // Formulation): the dual-weighted gap would carry a bias of
          // -kappa h^2 / 6 (kappa: curvature of the gap function), which on
          // coarse faces reaches the size of micrometre clearances.
          // The weighted normal (not of unit length on a curved face):
          // with it the master coefficients of each direction sum to the
          // slave's, so action equals reaction exactly.
          s.normal = normals[i] / s.weight;
          s.master_dofs.clear();
          s.master_coefficients.clear();
          for (const auto &[m, value] : coef[i])
            if (std::abs(value) > 1e-14 * s.weight)
              {
                s.master_dofs.push_back(m);
                s.master_coefficients.push_back(value / s.weight);
              }
        }
    }



    template <int dim>
    void
    ContactProblem<dim>::find_tied_nodes()
    {
      ties.clear();
      if (!with_ties)
        return;
      const auto &fe          = problem->finite_element();
      const auto &mapping     = problem->mapping();
      const auto &hanging     = problem->hanging_node_constraints();
      const auto &unit_points = fe.base_element(0).get_unit_support_points();
      std::set<dealii::types::global_dof_index>    done;
      std::vector<dealii::types::global_dof_index> indices(
        fe.n_dofs_per_cell());
      for (const auto &cell : problem->dof_handler().active_cell_iterators())
        {
          if (cell->material_id() != tied_body)
            continue;
          for (const unsigned int f : cell->face_indices())
            {
              if (!cell->face(f)->at_boundary() ||
                  cell->face(f)->boundary_id() != tied_surface)
                continue;
              cell->get_dof_indices(indices);
              for (unsigned int k = 0; k < fe.n_dofs_per_face(f); ++k)
                {
                  const unsigned int i = fe.face_to_cell_index(k, f);
                  const auto [component, node] =
                    fe.system_to_component_index(i);
                  if (component != 0 || !done.insert(indices[i]).second ||
                      hanging.is_constrained(indices[i]))
                    continue;
                  const dealii::Point<dim> x =
                    mapping.transform_unit_to_real_cell(cell,
                                                        unit_points[node]);
                  const auto [nearest, d] = nearest_cylinder(cylinders, x);
                  dealii::Point<dim> P    = x;
                  for (unsigned int c = 0; c < 2; ++c)
                    P[c] = cylinders[nearest].centre[c] +
                           cylinders[nearest].radius *
                             (x[c] - cylinders[nearest].centre[c]) / d;
                  TiedNode<dim> t;
                  for (unsigned int c = 0; c < dim; ++c)
                    t.dofs[c] = indices[fe.component_to_system_index(c, node)];
                  AssertThrow(master_weights(nearest, P, t.masters, t.weights),
                              dealii::ExcMessage(
                                "contact: a tied node has no master face "
                                "(body " +
                                std::to_string(cylinders[nearest].body) +
                                ")."));
                  ties.push_back(t);
                }
            }
        }
    }



    template <int dim>
    void
    ContactProblem<dim>::set_fixed_dofs(
      const std::vector<dealii::types::global_dof_index> &dofs)
    {
      fixed = dofs;
    }



    template <int dim>
    void
    ContactProblem<dim>::set_load(
      const std::map<dealii::types::global_dof_index, double> &g)
    {
      load = g;
    }



    template <int dim>
    void
    ContactProblem<dim>::set_placement(
      const std::function<dealii::Point<dim>(dealii::types::material_id,
                                             const dealii::Point<dim> &)> &p)
    {
      placement = p;
    }



    template <int dim>
    void
    ContactProblem<dim>::update_geometry()
    {
      std::set<dealii::types::global_dof_index> was_active;
      for (const unsigned int i : active)
        was_active.insert(slaves[i].dofs[0]);
      find_slave_nodes();
      ghost_master_dofs();
      active.clear();
      for (unsigned int i = 0; i < slaves.size(); ++i)
        if (!slaves[i].hanging && was_active.count(slaves[i].dofs[0]))
          active.insert(i);
      reset_slave_results();
    }



    template <int dim>
    void
    ContactProblem<dim>::initialise_active_set(
      const std::function<bool(const SlaveNode<dim> &)> &predicate)
    {
      active.clear();
      for (unsigned int i = 0; i < slaves.size(); ++i)
        if (!slaves[i].hanging && predicate(slaves[i]))
          active.insert(i);
    }



    template <int dim>
    std::vector<std::pair<SlaveNode<dim>, bool>>
    ContactProblem<dim>::active_set_snapshot() const
    {
      std::vector<std::pair<SlaveNode<dim>, bool>> snapshot;
      for (unsigned int i = 0; i < slaves.size(); ++i)
        {
          SlaveNode<dim> s = slaves[i];
          s.master_dofs.clear();
          s.master_coefficients.clear();
          snapshot.emplace_back(s, active.count(i) > 0);
        }
      return snapshot;
    }



    template <int dim>
    void
    ContactProblem<dim>::transfer_active_set(
      const std::vector<std::pair<SlaveNode<dim>, bool>> &snapshot)
    {
      std::map<std::pair<unsigned int, unsigned int>,
               std::vector<const std::pair<SlaveNode<dim>, bool> *>>
        groups;
      for (const auto &entry : snapshot)
        groups[{entry.first.body, entry.first.cylinder}].push_back(&entry);
      active.clear();
      for (unsigned int i = 0; i < slaves.size(); ++i)
        {
          if (slaves[i].hanging)
            continue;
          const auto g = groups.find({slaves[i].body, slaves[i].cylinder});
          if (g == groups.end())
            continue;
          double best = std::numeric_limits<double>::max();
          bool   flag = false;
          for (const auto *entry : g->second)
            {
              const double d =
                entry->first.position.distance(slaves[i].position);
              if (d < best)
                {
                  best = d;
                  flag = entry->second;
                }
            }
          if (flag)
            active.insert(i);
        }
    }



    template <int dim>
    std::function<void(dealii::AffineConstraints<double> &)>
    ContactProblem<dim>::constraints(const bool   with_gaps,
                                     const double beta) const
    {
      return [this, with_gaps, beta](dealii::AffineConstraints<double> &c) {
        for (const auto d : fixed)
          if (c.can_store_line(d) && !c.is_constrained(d))
            c.add_line(d);
        for (const auto &[d, g] : load)
          if (c.can_store_line(d) && !c.is_constrained(d))
            {
              c.add_line(d);
              c.set_inhomogeneity(d, beta * g);
            }
        for (const TiedNode<dim> &t : ties)
          for (unsigned int comp = 0; comp < dim; ++comp)
            {
              const auto d = t.dofs[comp];
              if (!c.can_store_line(d) || c.is_constrained(d))
                continue;
              c.add_line(d);
              for (unsigned int a = 0; a < t.masters[comp].size(); ++a)
                c.add_entry(d, t.masters[comp][a], t.weights[comp][a]);
            }
        // Active nodes: n . (u_s - u_M(P)) = -gap0, eliminating the
        // dominant normal component.
        for (const unsigned int i : active)
          {
            const SlaveNode<dim> &s = slaves[i];
            const unsigned int    k =
              std::abs(s.normal[0]) >= std::abs(s.normal[1]) ? 0 : 1;
            const auto dk = s.dofs[k];
            if (!c.can_store_line(dk) || c.is_constrained(dk))
              continue;
            c.add_line(dk);
            for (unsigned int comp = 0; comp < 2; ++comp)
              if (comp != k)
                c.add_entry(dk, s.dofs[comp], -s.normal[comp] / s.normal[k]);
            for (unsigned int a = 0; a < s.master_dofs.size(); ++a)
              c.add_entry(dk,
                          s.master_dofs[a],
                          s.master_coefficients[a] / s.normal[k]);
            c.set_inhomogeneity(dk, with_gaps ? -s.gap0 / s.normal[k] : 0.);
          }
      };
    }



    template <int dim>
    double
    ContactProblem<dim>::reaction(
      const dealii::TrilinosWrappers::MPI::Vector &f) const
    {
      double q = 0;
      for (const auto &[d, g] : load)
        if (problem->locally_owned_dofs().is_element(d))
          q += g * f[d];
      return dealii::Utilities::MPI::sum(q, comm);
    }



    template <int dim>
    ContactState
    ContactProblem<dim>::solve_load(const double       target,
                                    const std::string &label)
    {
      return solve_state(true, target, label);
    }



    template <int dim>
    ContactState
    ContactProblem<dim>::solve_displacement(const double       beta,
                                            const std::string &label)
    {
      return solve_state(false, beta, label);
    }



    template <int dim>
    ContactState
    ContactProblem<dim>::solve_state(const bool         load_control,
                                     const double       value,
                                     const std::string &label)
    {
      ContactState                          state;
      dealii::TrilinosWrappers::MPI::Vector u0, u1, f0, f1;
      std::vector<std::set<unsigned int>>   history;
      const auto &owned = problem->locally_owned_dofs();
      for (unsigned int it = 0;; ++it)
        {
          AssertThrow(it < settings.max_iterations,
                      dealii::ExcMessage(
                        "contact: the active set did not settle in " +
                        std::to_string(settings.max_iterations) +
                        " iterations (Contact/Maximum active set iterations) "
                        "at " +
                        label + "."));
          dealii::Timer clock(comm, true);
          problem->setup_constraints(
            {constraints(true, 0.), constraints(false, 1.)});
          problem->assemble_sets({});
          const double       t_assemble = clock.wall_time();
          const unsigned int n0         = problem->solve_set(0,
                                                     settings.solver,
                                                     settings.solver_tolerance,
                                                     u0);
          const double       t_solve0   = clock.wall_time();
          const unsigned int n1         = problem->solve_set(1,
                                                     settings.solver,
                                                     settings.solver_tolerance,
                                                     u1);
          state.linear_iterations += n0 + n1;
          if (std::getenv("CYCLOID_DEBUG") &&
              dealii::Utilities::MPI::this_mpi_process(comm) == 0)
            std::cerr << "  [active set] " << label << ", iteration " << it
                      << ": constraints+assembly " << t_assemble
                      << " s, solve 0 (with preconditioner set-up) "
                      << t_solve0 - t_assemble << " s / " << n0
                      << " it, solve 1 " << clock.wall_time() - t_solve0
                      << " s / " << n1 << " it" << std::endl;
          f0               = problem->effective_forces(u0, true);
          f1               = problem->effective_forces(u1, false);
          const double q0  = reaction(f0);
          const double q1  = reaction(f1);
          state.tangent    = q1;
          state.iterations = it + 1;
          if (load_control)
            {
              AssertThrow(
                std::abs(q1) > 0,
                dealii::ExcMessage(
                  "contact: no contact node carries the load at " + label +
                  " (the loaded body moves freely for this active set); "
                  "check the clearances and the search distance."));
              state.beta = (value - q0) / q1;
            }
          else
            state.beta = value;
          state.reaction = q0 + state.beta * q1;

          // New active set from the owned nodes, merged over the ranks.
          std::vector<unsigned int> mine;
          std::vector<double>       my_gaps(slaves.size(), 0.);
          for (unsigned int i = 0; i < slaves.size(); ++i)
            {
              const SlaveNode<dim> &s = slaves[i];
              if (s.hanging || !owned.is_element(s.dofs[0]))
                continue;
              double gap = s.gap0, lambda = 0;
              for (unsigned int c = 0; c < 2; ++c)
                {
                  gap +=
                    s.normal[c] * (u0[s.dofs[c]] + state.beta * u1[s.dofs[c]]);
                  lambda +=
                    s.normal[c] * (f0[s.dofs[c]] + state.beta * f1[s.dofs[c]]);
                }
              for (unsigned int a = 0; a < s.master_dofs.size(); ++a)
                gap -=
                  s.master_coefficients[a] *
                  (u0[s.master_dofs[a]] + state.beta * u1[s.master_dofs[a]]);
              my_gaps[i]            = gap;
              const bool was_active = active.count(i);
              if ((was_active && lambda > 0) || (!was_active && gap < 0))
                mine.push_back(i);
            }
          std::set<unsigned int> next;
          for (const auto &part :
               dealii::Utilities::MPI::all_gather(comm, mine))
            next.insert(part.begin(), part.end());
          dealii::Utilities::MPI::sum(my_gaps, comm, gaps);
          if (std::getenv("CYCLOID_DEBUG") &&
              dealii::Utilities::MPI::this_mpi_process(comm) == 0)
            std::cerr << "  [active set] " << label << ", iteration " << it
                      << ": beta " << state.beta << ", Q0 " << q0 << ", Q1 "
                      << q1 << ", active " << active.size() << " -> "
                      << next.size() << std::endl;
          if (next == active)
            break;
          AssertThrow(std::find(history.begin(), history.end(), next) ==
                        history.end(),
                      dealii::ExcMessage(
                        "contact: the active set cycles (a set seen before "
                        "returned at iteration " +
                        std::to_string(it) + ") at " + label + "."));
          history.push_back(active);
          active = next;
        }

      // The state u = u0 + beta u1 and its reactions.
      {
        dealii::TrilinosWrappers::MPI::Vector a(owned, comm), b(owned, comm);
        a = u0;
        b = u1;
        a.add(state.beta, b);
        u_last.reinit(owned, problem->locally_relevant_dofs(), comm);
        u_last = a;
      }
      const auto [r, f] = problem->residual_norms(u_last, 0);
      state.residual    = f > 0 ? r / f : 0.;
      AssertThrow(state.residual <= settings.residual_tolerance,
                  dealii::ExcMessage(
                    "contact: the converged active set leaves an equilibrium "
                    "residual of " +
                    std::to_string(state.residual) + " (relative) at " + label +
                    ", above " + std::to_string(settings.residual_tolerance) +
                    "; tighten Solver/Relative tolerance."));
      std::vector<double> mine(slaves.size() * dim, 0.),
        all(slaves.size() * dim);
      for (const unsigned int i : active)
        if (owned.is_element(slaves[i].dofs[0]))
          for (unsigned int c = 0; c < dim; ++c)
            mine[i * dim + c] =
              f0[slaves[i].dofs[c]] + state.beta * f1[slaves[i].dofs[c]];
      dealii::Utilities::MPI::sum(mine, comm, all);
      for (unsigned int i = 0; i < slaves.size(); ++i)
        for (unsigned int c = 0; c < dim; ++c)
          reactions[i][c] = all[i * dim + c];
      state.n_active = active.size();
      return state;
    }



    namespace
    {
      /** Von Mises stress per body material (2D: plane strain, sigma_zz =
       * lambda tr(eps)). */
      template <int dim>
      class VonMises : public dealii::DataPostprocessorScalar<dim>
      {
      public:
        explicit VonMises(
          const std::map<dealii::types::material_id,
                         parameters::ElasticMaterial> &materials)
          : dealii::DataPostprocessorScalar<dim>("von_Mises",
                                                 dealii::update_gradients)
          , materials(materials)
        {}

        void
        evaluate_vector_field(
          const dealii::DataPostprocessorInputs::Vector<dim> &inputs,
          std::vector<dealii::Vector<double>> &computed) const override
        {
          const auto   cell = inputs.template get_cell<dim>();
          const auto  &m    = materials.at(cell->material_id());
          const double E = m.youngs_modulus, nu = m.poissons_ratio;
          const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
          const double mu     = E / (2 * (1 + nu));
          for (unsigned int q = 0; q < computed.size(); ++q)
            {
              const auto &g = inputs.solution_gradients[q];
              double      eps[3][3]{};
              for (unsigned int a = 0; a < dim; ++a)
                for (unsigned int b = 0; b < dim; ++b)
                  eps[a][b] = 0.5 * (g[a][b] + g[b][a]);
              const double tr = eps[0][0] + eps[1][1] + eps[2][2];
              double       s[3][3];
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int b = 0; b < 3; ++b)
                  s[a][b] = 2 * mu * eps[a][b] + (a == b ? lambda * tr : 0.);
              computed[q](0) =
                std::sqrt(0.5 * ((s[0][0] - s[1][1]) * (s[0][0] - s[1][1]) +
                                 (s[1][1] - s[2][2]) * (s[1][1] - s[2][2]) +
                                 (s[2][2] - s[0][0]) * (s[2][2] - s[0][0])) +
                          3 * (s[0][1] * s[0][1] + s[1][2] * s[1][2] +
                               s[0][2] * s[0][2]));
            }
        }

      private:
        const std::map<dealii::types::material_id, parameters::ElasticMaterial>
          &materials;
      };
    } // namespace



    template <int dim>
    void
    ContactProblem<dim>::write_vtu(const std::string &directory,
                                   const std::string &name) const
    {
      // Nodal contact fields, one scalar per displacement component of a
      // slave node: x slot the contact pressure (normal reaction / node
      // weight, MPa), y slot the active flag, z slot (3D) the gap [um].
      const auto &owned = problem->locally_owned_dofs();
      dealii::TrilinosWrappers::MPI::Vector contact(owned, comm);
      for (unsigned int i = 0; i < slaves.size(); ++i)
        {
          double lambda = 0;
          for (unsigned int c = 0; c < dim; ++c)
            lambda += reactions[i][c] * slaves[i].normal[c];
          const double values[3] = {slaves[i].weight > 0 ?
                                      lambda / slaves[i].weight :
                                      0.,
                                    active.count(i) ? 1. : 0.,
                                    gaps[i] * 1e3};
          for (unsigned int c = 0; c < dim; ++c)
            if (owned.is_element(slaves[i].dofs[c]))
              contact[slaves[i].dofs[c]] = values[c];
        }
      contact.compress(dealii::VectorOperation::insert);
      dealii::TrilinosWrappers::MPI::Vector contact_g(
        owned, problem->locally_relevant_dofs(), comm);
      contact_g = contact;

      dealii::DataOut<dim> data_out;
      data_out.attach_dof_handler(problem->dof_handler());
      const std::vector<
        dealii::DataComponentInterpretation::DataComponentInterpretation>
        vector(
          dim,
          dealii::DataComponentInterpretation::component_is_part_of_vector);
      data_out.add_data_vector(u_last,
                               std::vector<std::string>(dim, "displacement"),
                               dealii::DataOut<dim>::type_dof_data,
                               vector);
      std::vector<std::string> names{"contact_pressure",
                                     "active_set",
                                     "gap_um"};
      names.resize(dim);
      data_out.add_data_vector(contact_g, names);
      const VonMises<dim> von_mises(materials);
      data_out.add_data_vector(u_last, von_mises);
      const auto           &tria = problem->dof_handler().get_triangulation();
      dealii::Vector<float> body(tria.n_active_cells()),
        rank(tria.n_active_cells());
      for (const auto &cell : tria.active_cell_iterators())
        {
          body(cell->active_cell_index()) = cell->material_id();
          rank(cell->active_cell_index()) = cell->subdomain_id();
        }
      data_out.add_data_vector(body, "body_id");
      data_out.add_data_vector(rank, "mpi_rank");
      data_out.build_patches(problem->mapping(),
                             problem->finite_element().degree,
                             dealii::DataOut<dim>::curved_inner_cells);

      const unsigned int r = dealii::Utilities::MPI::this_mpi_process(comm);
      {
        std::ofstream out(directory + "/" + name + "." +
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
          std::ofstream pvtu(directory + "/" + name + ".pvtu");
          data_out.write_pvtu_record(pvtu, pieces);
        }
    }



    template class ContactProblem<2>;
    template class ContactProblem<3>;
  } // namespace contact
} // namespace cycloid

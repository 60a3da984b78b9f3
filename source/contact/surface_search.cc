#include <deal.II/base/exceptions.h>

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/distributed/tria_base.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>

#include <cycloid/contact/surface_search.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

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

      /** Angle of @p x about the axis @p c in the xy plane. */
      template <int dim>
      double
      angle(const dealii::Point<dim> &x, const dealii::Point<2> &c)
      {
        return std::atan2(x[1] - c[1], x[0] - c[0]);
      }

      /** A point's coordinates appended to @p out. */
      template <int dim>
      void
      pack_point(const dealii::Point<dim> &x, std::vector<double> &out)
      {
        for (unsigned int c = 0; c < dim; ++c)
          out.push_back(x[c]);
      }

      /** The point at @p in, which then moves past it. */
      template <int dim>
      dealii::Point<dim>
      unpack_point(const double *&in)
      {
        dealii::Point<dim> x;
        for (unsigned int c = 0; c < dim; ++c)
          x[c] = *in++;
        return x;
      }

      /** |a| with a reduced to [-pi, pi]. */
      double
      angular_distance(const double a)
      {
        return std::abs(std::remainder(a, 2. * dealii::numbers::PI));
      }


      /** Face @p f of @p cell (of a cylinder centred at @p c) as data. */
      template <int dim>
      typename SurfaceSearch<dim>::MasterFace
      master_face(
        const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
        const unsigned int                                            f,
        const dealii::Point<2>                                       &c)
      {
        typename SurfaceSearch<dim>::MasterFace m;
        m.face = f;
        for (unsigned int v = 0; v < m.vertices.size(); ++v)
          m.vertices[v] = cell->vertex(
            dealii::GeometryInfo<dim>::face_to_cell_vertices(f, v));
        m.dofs.resize(cell->get_fe().n_dofs_per_cell());
        cell->get_dof_indices(m.dofs);
        // (centre angle, half angular width, z min, z max)
        const double a0 = angle(cell->face(f)->center(), c);
        m.box           = {{a0, 0., 1e300, -1e300}};
        for (const unsigned int v : cell->face(f)->vertex_indices())
          {
            const auto x = cell->face(f)->vertex(v);
            m.box[1] = std::max(m.box[1], angular_distance(angle(x, c) - a0));
            m.box[2] = std::min(m.box[2], x[dim - 1]);
            m.box[3] = std::max(m.box[3], x[dim - 1]);
          }
        return m;
      }

      /** Every rank's master faces @p mine (per cylinder), in rank order.
       * Record: cylinder, face, vertices, box, number of DoFs, DoFs (DoF
       * indices are exact in a double below 2^53). */
      template <int dim>
      std::vector<std::vector<typename SurfaceSearch<dim>::MasterFace>>
      gather_master_faces(
        const std::vector<std::vector<typename SurfaceSearch<dim>::MasterFace>>
                      &mine,
        const MPI_Comm comm)
      {
        std::vector<double> packed;
        for (unsigned int j = 0; j < mine.size(); ++j)
          for (const auto &m : mine[j])
            {
              packed.push_back(j);
              packed.push_back(m.face);
              for (const auto &x : m.vertices)
                pack_point<dim>(x, packed);
              packed.insert(packed.end(), m.box.begin(), m.box.end());
              packed.push_back(m.dofs.size());
              packed.insert(packed.end(), m.dofs.begin(), m.dofs.end());
            }
        const std::vector<double> all = gather_all(comm, packed);
        std::vector<std::vector<typename SurfaceSearch<dim>::MasterFace>> faces(
          mine.size());
        const double *in = all.data();
        while (in < all.data() + all.size())
          {
            typename SurfaceSearch<dim>::MasterFace m;
            const auto j = static_cast<unsigned int>(*in++);
            m.face       = static_cast<unsigned int>(*in++);
            for (auto &x : m.vertices)
              x = unpack_point<dim>(in);
            for (auto &b : m.box)
              b = *in++;
            m.dofs.resize(static_cast<std::size_t>(*in++));
            for (auto &d : m.dofs)
              d = static_cast<dealii::types::global_dof_index>(*in++);
            faces[j].push_back(std::move(m));
          }
        return faces;
      }


      /** Every rank's slave nodes @p mine, merged: a node met on several
       * ranks' faces sums their weights (and is hanging if any rank says
       * so); ordered by x DoF. */
      template <int dim>
      std::vector<SlaveNode<dim>>
      gather_slave_nodes(const std::vector<SlaveNode<dim>> &mine,
                         const MPI_Comm                     comm)
      {
        std::vector<double> packed;
        for (const auto &s : mine)
          {
            packed.insert(packed.end(), s.dofs.begin(), s.dofs.end());
            packed.push_back(s.body);
            packed.push_back(s.cylinder);
            pack_point<dim>(s.position, packed);
            pack_point<dim>(dealii::Point<dim>(s.normal), packed);
            packed.push_back(s.gap0);
            packed.push_back(s.weight);
            packed.push_back(s.hanging);
          }
        const std::vector<double> all = gather_all(comm, packed);
        std::map<dealii::types::global_dof_index, SlaveNode<dim>> merged;
        const double *in = all.data();
        while (in < all.data() + all.size())
          {
            SlaveNode<dim> s;
            for (auto &d : s.dofs)
              d = static_cast<dealii::types::global_dof_index>(*in++);
            s.body     = static_cast<dealii::types::material_id>(*in++);
            s.cylinder = static_cast<unsigned int>(*in++);
            s.position = unpack_point<dim>(in);
            s.normal   = unpack_point<dim>(in);
            s.gap0     = *in++;
            s.weight   = *in++;
            s.hanging  = *in++ != 0.;
            const auto [it, added] = merged.emplace(s.dofs[0], s);
            if (!added)
              {
                it->second.weight += s.weight;
                it->second.hanging = it->second.hanging || s.hanging;
              }
          }
        std::vector<SlaveNode<dim>> slaves;
        for (auto &entry : merged)
          slaves.push_back(std::move(entry.second));
        return slaves;
      }
    } // namespace



    template <int dim>
    SurfaceSearch<dim>::SurfaceSearch(
      const elasticity::LinearElasticity<dim> &problem)
      : problem(problem)
    {}



    std::vector<double>
    gather_all(const MPI_Comm comm, const std::vector<double> &local)
    {
      std::vector<double> all;
      for (const auto &part : dealii::Utilities::MPI::all_gather(comm, local))
        all.insert(all.end(), part.begin(), part.end());
      return all;
    }



    template <int dim>
    bool
    SurfaceSearch<dim>::distributed() const
    {
      return dynamic_cast<
               const dealii::parallel::DistributedTriangulationBase<dim> *>(
               &problem.dof_handler().get_triangulation()) != nullptr;
    }



    template <int dim>
    MPI_Comm
    SurfaceSearch<dim>::communicator() const
    {
      return problem.dof_handler().get_triangulation().get_communicator();
    }



    template <int dim>
    void
    SurfaceSearch<dim>::set_contact(
      const std::set<dealii::types::material_id> &bodies,
      const dealii::types::boundary_id            surface,
      const std::vector<MasterCylinder>          &cylinders,
      const bool                                  deformable_masters)
    {
      slave_bodies  = bodies;
      slave_surface = surface;
      masters       = cylinders;
      deformable    = deformable_masters;
    }



    template <int dim>
    void
    SurfaceSearch<dim>::set_ties(const dealii::types::material_id body,
                                 const dealii::types::boundary_id surface)
    {
      with_ties    = true;
      tied_body    = body;
      tied_surface = surface;
    }



    template <int dim>
    void
    SurfaceSearch<dim>::set_placement(const Placement &p)
    {
      placement = p;
    }



    template <int dim>
    dealii::Point<dim>
    SurfaceSearch<dim>::place(const dealii::types::material_id body,
                              const dealii::Point<dim>        &x) const
    {
      return placement ? placement(body, x) : x;
    }



    template <int dim>
    dealii::Tensor<1, dim>
    SurfaceSearch<dim>::normal(const unsigned int        j,
                               const dealii::Point<dim> &x) const
    {
      const auto            &c = masters[j].centre;
      const double           d = planar_distance(x, c);
      dealii::Tensor<1, dim> n;
      for (unsigned int k = 0; k < 2; ++k)
        n[k] = (x[k] - c[k]) / d;
      return n;
    }



    template <int dim>
    dealii::Point<dim>
    SurfaceSearch<dim>::project(const unsigned int            j,
                                const dealii::Point<dim>     &x,
                                const dealii::Tensor<1, dim> &n) const
    {
      const MasterCylinder &m = masters[j];
      dealii::Point<dim>    P = x;
      for (unsigned int c = 0; c < 2; ++c)
        P[c] = m.centre[c] + m.radius * n[c];
      return P;
    }



    template <int dim>
    std::vector<typename SurfaceSearch<dim>::Face>
    SurfaceSearch<dim>::boundary_faces(
      const std::function<bool(dealii::types::material_id)> &body_matches,
      const dealii::types::boundary_id                       surface) const
    {
      std::vector<Face> faces;
      const bool        own_only = distributed();
      for (const auto &cell : problem.dof_handler().active_cell_iterators())
        if ((!own_only || cell->is_locally_owned()) &&
            body_matches(cell->material_id()))
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == surface)
              faces.emplace_back(cell, f);
      return faces;
    }



    template <int dim>
    std::vector<typename SurfaceSearch<dim>::Face>
    SurfaceSearch<dim>::slave_faces() const
    {
      return boundary_faces(
        [this](const dealii::types::material_id m) {
          return slave_bodies.count(m) > 0;
        },
        slave_surface);
    }



    template <int dim>
    void
    SurfaceSearch<dim>::collect_master_faces()
    {
      master_faces.assign(masters.size(), {});
      if (!deformable && !with_ties)
        return;
      std::map<dealii::types::material_id, unsigned int> by_body;
      for (unsigned int j = 0; j < masters.size(); ++j)
        by_body[masters[j].body] = j;
      const bool own_only = distributed();
      for (const auto &cell : problem.dof_handler().active_cell_iterators())
        {
          const auto it = by_body.find(cell->material_id());
          if (it == by_body.end() || (own_only && !cell->is_locally_owned()))
            continue;
          const unsigned int j = it->second;
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == masters[j].surface)
              master_faces[j].push_back(
                master_face<dim>(cell, f, masters[j].centre));
        }
      if (own_only)
        master_faces = gather_master_faces<dim>(master_faces, communicator());
    }



    template <int dim>
    bool
    SurfaceSearch<dim>::unit_point_on_face(const unsigned int        j,
                                           const MasterFace         &face,
                                           const dealii::Point<dim> &P,
                                           const double              theta,
                                           dealii::Point<dim>       &unit) const
    {
      // Unit coordinates of P on a face from the (angle, z) coordinates of
      // its vertices on the cylinder: the manifold places refined vertices
      // and the mapping's support points uniformly in angle and z, so the
      // bilinear (linear in 2D) interpolation of (angle, z) is exact.
      const MasterCylinder             &m               = masters[j];
      const unsigned int                f               = face.face;
      constexpr unsigned int            n_face_vertices = 1u << (dim - 1);
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
          const auto &x = face.vertices[v];
          rel[v][0]     = m.radius * std::remainder(angle(x, m.centre) - theta,
                                                2. * dealii::numbers::PI);
          rel[v][1]     = dim == 3 ? x[dim - 1] - P[dim - 1] : 0.;
          const auto u  = dealii::GeometryInfo<dim>::unit_cell_vertex(cv);
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
        return false;
      unit        = dealii::Point<dim>();
      unit[f / 2] = f % 2;
      for (unsigned int a = 0; a < dim - 1; ++a)
        unit[axes[a]] = std::clamp(xi[a], 0., 1.);
      return true;
    }



    template <int dim>
    void
    SurfaceSearch<dim>::master_weights(
      const unsigned int                                             j,
      const dealii::Point<dim>                                      &P,
      std::array<std::vector<dealii::types::global_dof_index>, dim> &dofs,
      std::array<std::vector<double>, dim>                          &weights,
      const std::string                                             &what) const
    {
      const auto  &fe    = problem.finite_element();
      const double theta = angle(P, masters[j].centre);
      for (unsigned int k = 0; k < master_faces[j].size(); ++k)
        {
          // Quick rejection by the face's (angle, z) box.
          const auto &box = master_faces[j][k].box;
          if (angular_distance(theta - box[0]) > box[1] + 1e-9 ||
              (dim == 3 &&
               (P[dim - 1] < box[2] - 1e-9 || P[dim - 1] > box[3] + 1e-9)))
            continue;
          dealii::Point<dim> unit;
          if (!unit_point_on_face(j, master_faces[j][k], P, theta, unit))
            continue;
          const auto &indices = master_faces[j][k].dofs;
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
          return;
        }
      AssertThrow(false,
                  dealii::ExcMessage("contact: no face of master body " +
                                     std::to_string(masters[j].body) +
                                     " holds the projection of a " + what +
                                     "; is the master surface meshed?"));
    }



    template <int dim>
    std::vector<SlaveNode<dim>>
    SurfaceSearch<dim>::find_slave_nodes(const double search_distance) const
    {
      std::vector<SlaveNode<dim>> slaves;
      const auto                 &fe      = problem.finite_element();
      const auto                 &mapping = problem.mapping();
      const auto                 &hanging = problem.hanging_node_constraints();
      const dealii::QGauss<dim - 1> quadrature(fe.degree + 1);
      dealii::FEFaceValues<dim>     fe_face(mapping,
                                        fe,
                                        quadrature,
                                        dealii::update_values |
                                          dealii::update_JxW_values);
      const auto &unit_points = fe.base_element(0).get_unit_support_points();
      // Slave index of every node met so far (invalid: out of reach); a
      // node shared by several faces sums their weights.
      std::map<dealii::types::global_dof_index, unsigned int> index_of;
      std::vector<dealii::types::global_dof_index>            indices(
        fe.n_dofs_per_cell());
      for (const auto &[cell, f] : slave_faces())
        {
          cell->get_dof_indices(indices);
          fe_face.reinit(cell, f);
          for (unsigned int k = 0; k < fe.n_dofs_per_face(f); ++k)
            {
              const unsigned int i         = fe.face_to_cell_index(k, f);
              const auto [component, node] = fe.system_to_component_index(i);
              if (component != 0)
                continue;
              double w = 0;
              for (const unsigned int q : fe_face.quadrature_point_indices())
                w += fe_face.shape_value(i, q) * fe_face.JxW(q);
              const auto known = index_of.find(indices[i]);
              if (known != index_of.end())
                {
                  if (known->second != dealii::numbers::invalid_unsigned_int)
                    slaves[known->second].weight += w;
                  continue;
                }
              const dealii::Point<dim> x =
                place(cell->material_id(),
                      mapping.transform_unit_to_real_cell(cell,
                                                          unit_points[node]));
              const auto [nearest, d] = nearest_cylinder(masters, x);
              const double gap        = d - masters[nearest].radius;
              if (gap > search_distance)
                {
                  index_of[indices[i]] = dealii::numbers::invalid_unsigned_int;
                  continue;
                }
              SlaveNode<dim> s;
              s.body     = cell->material_id();
              s.cylinder = nearest;
              s.position = x;
              s.normal   = normal(nearest, x);
              s.gap0     = gap;
              s.weight   = w;
              for (unsigned int c = 0; c < dim; ++c)
                s.dofs[c] = indices[fe.component_to_system_index(c, node)];
              s.hanging            = hanging.is_constrained(s.dofs[0]);
              index_of[indices[i]] = slaves.size();
              slaves.push_back(s);
            }
        }
      return distributed() ? gather_slave_nodes(slaves, communicator()) :
                             slaves;
    }



    template <int dim>
    std::vector<TiedNode<dim>>
    SurfaceSearch<dim>::find_tied_nodes() const
    {
      std::vector<TiedNode<dim>> ties;
      if (!with_ties)
        return ties;
      for (const auto &[dofs, x] : tied_candidates())
        {
          const auto [nearest, d] = nearest_cylinder(masters, x);
          const MasterCylinder &m = masters[nearest];
          // R (x - c) / d rather than project()'s R ((x - c) / d): the
          // tie code's order of operations since it was written, kept
          // so that tied scenes reproduce their results bit for bit
          // (CG amplifies a last-bit change to ~1e-11).
          dealii::Point<dim> P = x;
          for (unsigned int c = 0; c < 2; ++c)
            P[c] = m.centre[c] + m.radius * (x[c] - m.centre[c]) / d;
          TiedNode<dim> t;
          t.dofs = dofs;
          master_weights(nearest, P, t.masters, t.weights, "tied node");
          ties.push_back(t);
        }
      return ties;
    }



    template <int dim>
    std::vector<std::pair<std::array<dealii::types::global_dof_index, dim>,
                          dealii::Point<dim>>>
    SurfaceSearch<dim>::tied_candidates() const
    {
      const auto &fe          = problem.finite_element();
      const auto &mapping     = problem.mapping();
      const auto &hanging     = problem.hanging_node_constraints();
      const auto &unit_points = fe.base_element(0).get_unit_support_points();
      std::set<dealii::types::global_dof_index>    done;
      std::vector<dealii::types::global_dof_index> indices(
        fe.n_dofs_per_cell());
      std::vector<double> packed;
      const auto          faces = boundary_faces(
        [this](const dealii::types::material_id m) { return m == tied_body; },
        tied_surface);
      for (const auto &[cell, f] : faces)
        {
          cell->get_dof_indices(indices);
          for (unsigned int k = 0; k < fe.n_dofs_per_face(f); ++k)
            {
              const unsigned int i         = fe.face_to_cell_index(k, f);
              const auto [component, node] = fe.system_to_component_index(i);
              if (component != 0 || !done.insert(indices[i]).second ||
                  hanging.is_constrained(indices[i]))
                continue;
              for (unsigned int c = 0; c < dim; ++c)
                packed.push_back(
                  indices[fe.component_to_system_index(c, node)]);
              pack_point<dim>(
                mapping.transform_unit_to_real_cell(cell, unit_points[node]),
                packed);
            }
        }
      // A distributed mesh: every rank's, each node once, by x DoF.
      if (distributed())
        packed = gather_all(communicator(), packed);
      std::vector<std::pair<std::array<dealii::types::global_dof_index, dim>,
                            dealii::Point<dim>>>
                                                candidates;
      std::set<dealii::types::global_dof_index> seen;
      for (const double *in = packed.data();
           in < packed.data() + packed.size();)
        {
          std::array<dealii::types::global_dof_index, dim> dofs;
          for (auto &d : dofs)
            d = static_cast<dealii::types::global_dof_index>(*in++);
          const dealii::Point<dim> x = unpack_point<dim>(in);
          if (seen.insert(dofs[0]).second)
            candidates.emplace_back(dofs, x);
        }
      if (distributed())
        std::sort(candidates.begin(),
                  candidates.end(),
                  [](const auto &a, const auto &b) {
                    return a.first[0] < b.first[0];
                  });
      return candidates;
    }



    template class SurfaceSearch<2>;
    template class SurfaceSearch<3>;
  } // namespace contact
} // namespace cycloid

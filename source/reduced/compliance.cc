#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <cycloid/mesh/ids.h>
#include <cycloid/reduced/compliance.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace cycloid
{
  namespace reduced
  {
    namespace
    {
      using Vector = dealii::TrilinosWrappers::MPI::Vector;

      /** Semi-elliptic pressure of unit line load and half-width @p w at
       * the tangential distance @p s from its centre [1/mm]. */
      double
      pressure(const double s, const double w)
      {
        return std::abs(s) < w ? 2. / (dealii::numbers::PI * w) *
                                   std::sqrt(1. - s * s / (w * w)) :
                                 0.;
      }



      /**
       * @brief The nodal load vectors of the contacts: a face quadrature
       * fine enough for a pressure narrower than a face, on the two
       * bodies of each contact.
       */
      template <int dim>
      class LoadAssembler
      {
      public:
        LoadAssembler(const elasticity::LinearElasticity<dim> &problem,
                      const double                             w)
          : problem(problem)
          , w(w)
          , quadrature(dealii::QIterated<dim - 1>(dealii::QGauss<1>(3), 8))
          , face_values(problem.mapping(),
                        problem.finite_element(),
                        quadrature,
                        dealii::update_values | dealii::update_JxW_values |
                          dealii::update_quadrature_points)
          , faces(loadable_faces())
        {}

        /** Integral of the pressure of contact @p p over the disc (first)
         * and the pin (second), summed over the ranks [-]. */
        std::pair<double, double>
        totals(const ContactPoint &p)
        {
          double sum[2] = {0., 0.};
          for_each_face(p, [&](const unsigned int side, const auto &) {
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              sum[side] += weight(p, side, q) * face_values.JxW(q);
          });
          const MPI_Comm comm = problem.dof_handler().get_communicator();
          return {dealii::Utilities::MPI::sum(sum[0], comm),
                  dealii::Utilities::MPI::sum(sum[1], comm)};
        }

        /** Assemble contact @p p's load, each body's side divided by its
         * @p total, into @p raw (plain; if given) and @p condensed (with the
         * constraints of set 0). */
        void
        assemble(const ContactPoint              &p,
                 const std::pair<double, double> &total,
                 Vector                          *raw,
                 Vector                          &condensed)
        {
          const auto            &fe       = problem.finite_element();
          const double           scale[2] = {-1. / total.first,
                                   total.second > 0 ? 1. / total.second : 0.};
          dealii::Vector<double> cell_rhs(fe.n_dofs_per_cell());
          std::vector<dealii::types::global_dof_index> indices(
            fe.n_dofs_per_cell());
          for_each_face(p, [&](const unsigned int side, const auto &cell) {
            cell_rhs = 0;
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                const double t =
                  scale[side] * weight(p, side, q) * face_values.JxW(q);
                if (t == 0)
                  continue;
                for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
                  {
                    const unsigned int c =
                      fe.system_to_component_index(i).first;
                    if (c < 2)
                      cell_rhs(i) +=
                        t * normal(p, side)[c] * face_values.shape_value(i, q);
                  }
              }
            cell->get_dof_indices(indices);
            if (raw)
              raw->add(indices, cell_rhs);
            problem.constraints().distribute_local_to_global(cell_rhs,
                                                             indices,
                                                             condensed);
          });
        }

      private:
        /** Centre of contact @p p's load on body @p side (0 disc, 1 pin),
         * in the mesh. */
        dealii::Point<2>
        centre(const ContactPoint &p, const unsigned int side) const
        {
          return side == 0 ? p.disc_point : p.point + p.clearance * p.normal;
        }

        /** The normal of contact @p p on body @p side, in the mesh. */
        static dealii::Tensor<1, 2>
        normal(const ContactPoint &p, const unsigned int side)
        {
          return side == 0 ? p.disc_normal : p.normal;
        }

        /** Pressure of contact @p p on body @p side at quadrature point
         * @p q of the current face [1/mm^(dim-1)]. */
        double
        weight(const ContactPoint &p,
               const unsigned int  side,
               const unsigned int  q) const
        {
          const dealii::Point<dim>  &x = face_values.quadrature_point(q);
          const dealii::Tensor<1, 2> d{
            {x[0] - centre(p, side)[0], x[1] - centre(p, side)[1]}};
          if (d.norm() > 2. * w)
            return 0.;
          const dealii::Tensor<1, 2> n = normal(p, side);
          const dealii::Tensor<1, 2> t{{-n[1], n[0]}};
          double                     value = pressure(d * t, w);
          if (dim == 3)
            value *= (x[dim - 1] >= p.z_min && x[dim - 1] <= p.z_max) ?
                       1. / (p.z_max - p.z_min) :
                       0.;
          return value;
        }

        /** Call @p f(side, cell) for each locally owned boundary face of
         * contact @p p's two bodies near its centre, with face_values
         * reinitialised on it (in the order of the cells). */
        template <typename F>
        void
        for_each_face(const ContactPoint &p, const F &f)
        {
          for (const auto &face : faces)
            {
              unsigned int side;
              if (face.material == mesh::ids::disc(p.disc) &&
                  face.boundary == mesh::ids::flank)
                side = 0;
              else if (face.material == mesh::ids::pin(p.pin) &&
                       face.boundary == mesh::ids::pin_surface)
                side = 1;
              else
                continue;
              if (face.centre.distance(centre(p, side)) >
                  2. * w + face.diameter)
                continue;
              face_values.reinit(face.cell, face.number);
              f(side, face.cell);
            }
        }

        /** @brief A locally owned boundary face that can carry a contact
         * load (a flank or a pin surface). */
        struct Face
        {
          typename dealii::DoFHandler<dim>::active_cell_iterator cell;
          unsigned int                                           number;
          dealii::types::material_id                             material;
          dealii::types::boundary_id                             boundary;
          dealii::Point<2>                                       centre;
          double                                                 diameter;
        };

        /** The faces a load can touch, in the order of the cells: found
         * once, not once per contact (84 passes over the 3D mesh took a
         * second). */
        std::vector<Face>
        loadable_faces() const
        {
          std::vector<Face> list;
          for (const auto &cell : problem.dof_handler().active_cell_iterators())
            {
              if (!cell->is_locally_owned() || !cell->at_boundary())
                continue;
              for (const unsigned int fn : cell->face_indices())
                {
                  const auto face = cell->face(fn);
                  if (!face->at_boundary() ||
                      (face->boundary_id() != mesh::ids::flank &&
                       face->boundary_id() != mesh::ids::pin_surface))
                    continue;
                  const auto c = face->center();
                  list.push_back({cell,
                                  fn,
                                  cell->material_id(),
                                  face->boundary_id(),
                                  dealii::Point<2>(c[0], c[1]),
                                  face->diameter()});
                }
            }
          return list;
        }

        const elasticity::LinearElasticity<dim> &problem;
        const double                             w;
        const dealii::Quadrature<dim - 1>        quadrature;
        dealii::FEFaceValues<dim>                face_values;
        const std::vector<Face>                  faces;
      };

      /** The load cases solved one at a time (the direct solver, or CG +
       * AMG), with a progress line about every tenth of them. */
      template <int dim>
      void
      solve_one_by_one(elasticity::LinearElasticity<dim> &problem,
                       const std::vector<Vector>         &raw,
                       const std::vector<Vector>         &condensed,
                       const elasticity::LinearSolver     solver,
                       const double                       tolerance,
                       Compliance                        &result,
                       std::ostream                      *progress)
      {
        const unsigned int n = raw.size();
        Vector             owned_u(problem.locally_owned_dofs(),
                       problem.dof_handler().get_communicator());
        const auto         start = std::chrono::steady_clock::now();
        double             shown = 0;
        for (unsigned int k = 0; k < n; ++k)
          {
            const double elapsed = std::chrono::duration<double>(
                                     std::chrono::steady_clock::now() - start)
                                     .count();
            if (progress && k > 0 &&
                (k % std::max(1u, n / 10) == 0 || elapsed - shown > 30))
              {
                *progress << "    load case " << k << "/" << n << ", "
                          << elapsed << " s" << std::endl;
                shown = elapsed;
              }
            problem.set_right_hand_side(0, condensed[k]);
            Vector u; // no warm start: the load cases are independent
            result.linear_iterations +=
              problem.solve_set(0, solver, tolerance, u);
            owned_u = u;
            for (unsigned int i = 0; i < n; ++i)
              result.matrix(i, k) = raw[i] * owned_u;
          }
      }
    } // namespace



    template <int dim>
    Compliance
    condense_compliance(contact::ContactProblem<dim>    &contact,
                        const std::vector<ContactPoint> &points,
                        const double                     w,
                        const elasticity::LinearSolver   solver,
                        const elasticity::Factorisation  factorisation,
                        const double                     tolerance,
                        dealii::TimerOutput             &timer,
                        std::ostream                    *progress)
    {
      auto              &problem = contact.elasticity_problem();
      const MPI_Comm     comm    = problem.dof_handler().get_communicator();
      const auto        &owned   = problem.locally_owned_dofs();
      const unsigned int n       = points.size();
      // The plain load vectors are needed by the one-by-one solves only
      // (the factorised form is F^T A^{-1} F of the condensed ones).
      const bool          direct = elasticity::is_direct(solver);
      std::vector<Vector> raw(direct ? 0 : n, Vector(owned, comm));
      std::vector<Vector> condensed(n, Vector(owned, comm));
      {
        dealii::TimerOutput::Scope scope(timer, "reduced: load vectors");
        LoadAssembler<dim>         loads(problem, w);
        for (unsigned int k = 0; k < n; ++k)
          {
            const auto total = loads.totals(points[k]);
            AssertThrow(total.first > 0,
                        dealii::ExcMessage(
                          "reduced model: no flank faces of disc " +
                          std::to_string(points[k].disc) +
                          " near its contact with pin " +
                          std::to_string(points[k].pin) +
                          " (the coarse mesh does not hold the contact "
                          "point)."));
            loads.assemble(points[k],
                           total,
                           direct ? nullptr : &raw[k],
                           condensed[k]);
            if (!direct)
              raw[k].compress(dealii::VectorOperation::add);
            condensed[k].compress(dealii::VectorOperation::add);
          }
      }
      Compliance result;
      result.matrix.reinit(n, n);
      {
        dealii::TimerOutput::Scope scope(timer, "reduced: solves");
        if (direct)
          {
            // One factorisation, every load case in one block: C = F^T
            // A^{-1} F (the constraints of set 0 are homogeneous, so f_i .
            // u_k is the condensed f_i . A^{-1} f_k).
            if (progress)
              *progress << "    factorising ("
                        << elasticity::to_string(factorisation)
                        << ") and solving " << n << " load cases as one block"
                        << std::endl;
            std::string statistics;
            result.matrix =
              problem.inverse_form(condensed, factorisation, &statistics);
            if (progress && !statistics.empty())
              *progress << "    " << statistics << std::endl;
          }
        else
          solve_one_by_one(
            problem, raw, condensed, solver, tolerance, result, progress);
      }
      double diagonal = 0;
      for (unsigned int i = 0; i < n; ++i)
        diagonal = std::max(diagonal, result.matrix(i, i));
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int k = 0; k < i; ++k)
          {
            const double a = result.matrix(i, k), b = result.matrix(k, i);
            result.asymmetry =
              std::max(result.asymmetry, std::abs(a - b) / diagonal);
            result.matrix(i, k) = result.matrix(k, i) = (a + b) / 2.;
          }
      return result;
    }



    template Compliance
    condense_compliance<2>(contact::ContactProblem<2> &,
                           const std::vector<ContactPoint> &,
                           const double,
                           const elasticity::LinearSolver,
                           const elasticity::Factorisation,
                           const double,
                           dealii::TimerOutput &,
                           std::ostream *);
    template Compliance
    condense_compliance<3>(contact::ContactProblem<3> &,
                           const std::vector<ContactPoint> &,
                           const double,
                           const elasticity::LinearSolver,
                           const elasticity::Factorisation,
                           const double,
                           dealii::TimerOutput &,
                           std::ostream *);
  } // namespace reduced
} // namespace cycloid

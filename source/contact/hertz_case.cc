#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/quadrature.h>

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/manifold_lib.h>

#include <cycloid/contact/contact_problem.h>
#include <cycloid/contact/hertz_case.h>
#include <cycloid/elasticity/support_points.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>

namespace cycloid
{
  namespace contact
  {
    double
    HertzCase::effective_radius() const
    {
      return 1. / (1. / r1 + (concave ? -1. : 1.) / r2);
    }



    double
    HertzCase::contact_modulus() const
    {
      return 1. / ((1 - nu1 * nu1) / e1 + (1 - nu2 * nu2) / e2);
    }



    double
    HertzCase::half_width() const
    {
      return std::sqrt(4 * force * effective_radius() /
                       (dealii::numbers::PI * contact_modulus()));
    }



    double
    HertzCase::peak_pressure() const
    {
      return 2 * force / (dealii::numbers::PI * half_width());
    }



    namespace
    {
      /** Whether every vertex of @p face lies on the circle (@p centre, @p r). */
      template <typename FaceIterator>
      bool
      on_circle(const FaceIterator     &face,
                const dealii::Point<2> &centre,
                const double            r)
      {
        for (const unsigned int v : face->vertex_indices())
          if (std::abs(face->vertex(v).distance(centre) - r) > 1e-9 * r)
            return false;
        return true;
      }



      /**
       * Merge the two coarse bodies of @p c (centres @p c1, @p c2) into
       * @p tria, mark bodies (material 1, 2) and surfaces (boundary and
       * manifold 1: body 1, 2: body 2's contact circle, 3: the rest), and
       * refine globally and then towards the contact point, where the
       * Hertz zone of half-width a has to be resolved.
       */
      void
      make_two_body_mesh(const HertzCase                            &c,
                         const dealii::Point<2>                     &c1,
                         const dealii::Point<2>                     &c2,
                         dealii::parallel::shared::Triangulation<2> &tria)
      {
        dealii::Triangulation<2> t1, t2;
        dealii::GridGenerator::hyper_ball(t1, c1, c.r1);
        if (c.concave)
          dealii::GridGenerator::hyper_shell(t2, c2, c.r2, 2 * c.r2, 8);
        else
          dealii::GridGenerator::hyper_ball(t2, c2, c.r2);
        dealii::GridGenerator::merge_triangulations(t1, t2, tria);

        for (const auto &cell : tria.active_cell_iterators())
          {
            cell->set_material_id(cell->center().distance(c1) < c.r1 ? 1 : 2);
            for (const unsigned int f : cell->face_indices())
              {
                const auto face = cell->face(f);
                if (!face->at_boundary())
                  continue;
                if (cell->material_id() == 1 && on_circle(face, c1, c.r1))
                  face->set_all_boundary_ids(1), face->set_all_manifold_ids(1);
                else if (on_circle(face, c2, c.r2))
                  face->set_all_boundary_ids(2), face->set_all_manifold_ids(2);
                else
                  face->set_all_boundary_ids(3), face->set_all_manifold_ids(3);
              }
          }
        tria.set_manifold(1, dealii::SphericalManifold<2>(c1));
        tria.set_manifold(2, dealii::SphericalManifold<2>(c2));
        tria.set_manifold(3, dealii::SphericalManifold<2>(c2));
        tria.refine_global(c.global_refinements);
        const double a = c.half_width();
        for (unsigned int k = 0; k < c.contact_refinements; ++k)
          {
            for (const auto &cell : tria.active_cell_iterators())
              if (cell->center().norm() < 3 * a + cell->diameter())
                cell->set_refine_flag();
            tria.execute_coarsening_and_refinement();
          }
      }



      /**
       * Hold body 2's core (convex) or the ring's outer surface (seat) and
       * load body 1's core by beta (0, -1): the load then follows from
       * solve_load() as a prescribed resultant.
       */
      void
      hold_and_load(const HertzCase        &c,
                    const dealii::Point<2> &c1,
                    const dealii::Point<2> &c2,
                    ContactProblem<2>      &problem)
      {
        const auto &el     = problem.elasticity();
        const auto &fe     = el.finite_element();
        auto        values = elasticity::support_point_values(el);
        std::vector<dealii::types::global_dof_index> indices(
          fe.n_dofs_per_cell());
        std::vector<dealii::types::global_dof_index>      fixed;
        std::map<dealii::types::global_dof_index, double> load;
        for (const auto &cell : el.dof_handler().active_cell_iterators())
          {
            cell->get_dof_indices(indices);
            values.reinit(cell);
            for (unsigned int i = 0; i < indices.size(); ++i)
              {
                const auto [comp, node] = fe.system_to_component_index(i);
                const auto &x           = values.quadrature_point(node);
                if (cell->material_id() == 1)
                  {
                    if (x.distance(c1) < 0.2 * c.r1)
                      load[indices[i]] = comp == 0 ? 0. : -1.;
                  }
                else if (c.concave ? x.distance(c2) > 2 * c.r2 * (1 - 1e-9) :
                                     x.distance(c2) < 0.3 * c.r2)
                  fixed.push_back(indices[i]);
              }
          }
        problem.set_fixed_dofs(fixed);
        problem.set_load(load);
      }



      /**
       * Fill @p r from the active slave nodes of the solved @p problem:
       * the half-width comes from the second moment of the nodal normal
       * forces over the arc length along body 2 (centre @p c2), which is
       * exact for Hertz's elliptic pressure.
       */
      void
      evaluate_contact_zone(const HertzCase         &c,
                            const dealii::Point<2>  &c2,
                            const ContactProblem<2> &problem,
                            HertzResult             &r)
      {
        double sum_f = 0, sum_fs2 = 0;
        r.h_contact        = 1e300;
        const auto &slaves = problem.slave_nodes();
        for (const unsigned int i : problem.active_set())
          {
            const auto  &s      = slaves[i];
            const double lambda = problem.slave_reactions()[i] * s.normal;
            // Arc length from the contact point along body 2's surface.
            const double phi = std::atan2(s.position[0] - c2[0],
                                          c.concave ? c2[1] - s.position[1] :
                                                      s.position[1] - c2[1]);
            const double arc = c.r2 * phi;
            sum_f += lambda;
            sum_fs2 += lambda * arc * arc;
            r.transmitted_force -= problem.slave_reactions()[i][1];
            r.peak_pressure = std::max(r.peak_pressure, lambda / s.weight);
            if (std::getenv("CYCLOID_DEBUG"))
              std::cerr << arc << ' ' << lambda / s.weight << ' ' << lambda
                        << ' ' << s.weight << std::endl;
            for (const unsigned int k : problem.active_set())
              if (k != i)
                r.h_contact = std::min(r.h_contact,
                                       s.position.distance(slaves[k].position));
          }
        r.contact_force = sum_f;
        r.half_width    = std::sqrt(4 * sum_fs2 / sum_f);
      }
    } // namespace



    HertzResult
    run_hertz_case(const HertzCase &c, const MPI_Comm comm)
    {
      AssertThrow(!c.concave || c.r2 > c.r1,
                  dealii::ExcMessage("Hertz case: a seat needs r2 > r1."));
      const auto start = std::chrono::steady_clock::now();
      // Contact at the origin; body 1 above it.
      const dealii::Point<2> c1(0, c.r1);
      const dealii::Point<2> c2(0, c.concave ? c.r2 : -c.r2);

      dealii::parallel::shared::Triangulation<2> tria(
        comm,
        dealii::Triangulation<2>::limit_level_difference_at_vertices,
        false,
        dealii::parallel::shared::Triangulation<2>::partition_metis);
      make_two_body_mesh(c, c1, c2, tria);

      const double    a = c.half_width();
      ContactSettings settings;
      // Candidates out to about 3 a: the undeformed gap there is
      // (3a)^2 / (2 R*).
      settings.search_distance = 9 * a * a / (2 * c.effective_radius());
      settings.solver          = elasticity::LinearSolver::cg_amg;
      settings.formulation     = c.formulation;
      ContactProblem<2> problem(tria,
                                c.degree,
                                {{1, {c.e1, c.nu1, 7850}},
                                 {2, {c.e2, c.nu2, 7850}}},
                                settings);
      problem.set_contact({2}, 2, {{c1, c.r1, 1, 1}}, true);
      problem.setup();
      hold_and_load(c, c1, c2, problem);
      // Cold start from the touching node only: the active set has to
      // grow to the Hertz zone by itself.
      problem.initialise_active_set(
        [&](const SlaveNode<2> &s) { return s.gap0 < 1e-9 * c.r1; });
      const ContactState state = problem.solve_load(c.force, "Hertz case");

      HertzResult r;
      r.n_dofs     = problem.elasticity().n_dofs();
      r.iterations = state.iterations;
      r.n_active   = state.n_active;
      evaluate_contact_zone(c, c2, problem, r);
      r.wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
      return r;
    }
  } // namespace contact
} // namespace cycloid

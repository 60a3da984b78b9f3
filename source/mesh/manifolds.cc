#include <deal.II/base/numbers.h>

#include <deal.II/grid/manifold_lib.h>

#include <cycloid/mesh/ids.h>
#include <cycloid/mesh/manifolds.h>

#include <cmath>

namespace cycloid
{
  namespace mesh
  {
    namespace
    {
      template <int dim>
      dealii::Tensor<1, dim - 1>
      profile_period(const unsigned int n_teeth)
      {
        dealii::Tensor<1, dim - 1> p;
        p[0] = 2. * dealii::numbers::PI * n_teeth;
        return p;
      }
    } // namespace



    template <int dim>
    CycloidProfileManifold<dim>::CycloidProfileManifold(
      const geometry::CycloidGeometry &geometry,
      const unsigned int               disc,
      const double                     psi)
      : dealii::ChartManifold<dim, dim, dim - 1>(
          profile_period<dim>(geometry.parameters().n_teeth))
      , geometry(geometry)
      , disc(disc)
      , psi(psi)
      , period(2. * dealii::numbers::PI * geometry.parameters().n_teeth)
    {}



    template <int dim>
    std::unique_ptr<dealii::Manifold<dim, dim>>
    CycloidProfileManifold<dim>::clone() const
    {
      return std::make_unique<CycloidProfileManifold<dim>>(geometry, disc, psi);
    }



    template <int dim>
    dealii::Point<dim - 1>
    CycloidProfileManifold<dim>::pull_back(const dealii::Point<dim> &x) const
    {
      const dealii::Point<2> q =
        geometry.to_disc(disc, psi, dealii::Point<2>(x[0], x[1]));
      double phi =
        std::fmod(geometry.disc_profile(disc).closest_point(q).phi, period);
      if (phi < 0)
        phi += period;
      dealii::Point<dim - 1> chart;
      chart[0] = phi;
      if (dim == 3)
        chart[dim - 2] = x[dim - 1];
      return chart;
    }



    template <int dim>
    dealii::Point<dim>
    CycloidProfileManifold<dim>::push_forward(
      const dealii::Point<dim - 1> &chart) const
    {
      const dealii::Point<2> p = geometry.to_housing(
        disc, psi, geometry.disc_profile(disc).profile(chart[0]).point);
      dealii::Point<dim> x;
      x[0] = p[0];
      x[1] = p[1];
      if (dim == 3)
        x[dim - 1] = chart[dim - 2];
      return x;
    }



    template <int dim>
    dealii::Point<dim>
    CycloidProfileManifold<dim>::project(const dealii::Point<dim> &x) const
    {
      return push_forward(pull_back(x));
    }



    template <>
    std::unique_ptr<dealii::Manifold<2, 2>>
    make_circle_manifold<2>(const dealii::Point<2> &centre)
    {
      return std::make_unique<dealii::PolarManifold<2>>(centre);
    }



    template <>
    std::unique_ptr<dealii::Manifold<3, 3>>
    make_circle_manifold<3>(const dealii::Point<2> &centre)
    {
      return std::make_unique<dealii::CylindricalManifold<3>>(
        dealii::Tensor<1, 3>({0., 0., 1.}),
        dealii::Point<3>(centre[0], centre[1], 0.));
    }



    template <int dim>
    dealii::Point<dim>
    project_to_circle(const dealii::Point<dim> &p,
                      const dealii::Point<2>   &centre,
                      const double              radius)
    {
      const double       dx = p[0] - centre[0], dy = p[1] - centre[1];
      const double       r      = std::sqrt(dx * dx + dy * dy);
      dealii::Point<dim> result = p;
      result[0]                 = centre[0] + dx * radius / r;
      result[1]                 = centre[1] + dy * radius / r;
      return result;
    }



    template <int dim>
    void
    attach_manifolds(const MeshSettings         &settings,
                     const double                psi,
                     dealii::Triangulation<dim> &tria)
    {
      const geometry::CycloidGeometry geo(settings.geometry);
      const auto                     &g = settings.geometry;
      for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
        {
          tria.set_manifold(ids::profile_manifold(d),
                            CycloidProfileManifold<dim>(geo, d, psi));
          tria.set_manifold(ids::bore_manifold(d),
                            *make_circle_manifold<dim>(
                              geo.disc_centre(d, psi)));
          for (unsigned int k = 0; k < g.n_crank_holes; ++k)
            {
              const auto h = geo.crank_hole_centre(d, k, psi);
              tria.set_manifold(ids::crank_hole_manifold(d, k),
                                *make_circle_manifold<dim>(h));
            }
        }
      for (unsigned int j = 0; j < g.n_pins; ++j)
        {
          tria.set_manifold(ids::pin_manifold(j),
                            *make_circle_manifold<dim>(geo.pin_centre(j)));
          tria.set_manifold(ids::pin_core_manifold(j),
                            *make_circle_manifold<dim>(geo.pin_centre(j)));
        }
      tria.set_manifold(ids::housing_manifold,
                        *make_circle_manifold<dim>(dealii::Point<2>()));
    }



    template class CycloidProfileManifold<2>;
    template class CycloidProfileManifold<3>;
    template dealii::Point<2>
    project_to_circle(const dealii::Point<2> &,
                      const dealii::Point<2> &,
                      double);
    template dealii::Point<3>
    project_to_circle(const dealii::Point<3> &,
                      const dealii::Point<2> &,
                      double);
    template void
    attach_manifolds<2>(const MeshSettings &,
                        const double,
                        dealii::Triangulation<2> &);
    template void
    attach_manifolds<3>(const MeshSettings &,
                        const double,
                        dealii::Triangulation<3> &);
  } // namespace mesh
} // namespace cycloid

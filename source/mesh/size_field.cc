#include <deal.II/base/numbers.h>

#include <cycloid/mesh/contact_refinement.h>
#include <cycloid/mesh/ids.h>
#include <cycloid/mesh/size_field.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <gmsh.h>

namespace cycloid
{
  namespace mesh
  {
    namespace internal
    {
      SizeField::SizeField(const MeshSettings              &settings,
                           const geometry::CycloidGeometry &geometry,
                           const double                     psi,
                           const double                     sweep,
                           const PinEntities               &pins)
        : m(settings.mesh)
        , pins(pins)
      {
        const auto &g = settings.geometry;
        points =
          contact_points_along(geometry, settings.scene.n_discs, psi, sweep);
        ring_radius       = geometry.root_radius() - 2. * g.pin_radius;
        pin_radius        = g.pin_radius;
        pin_circle_radius = geometry.pin_circle_radius();
        for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
          {
            disc_centres.push_back(geometry.disc_centre(d, psi));
            for (const Circle &c :
                 circles_of(settings, geometry, psi, ids::disc(d)))
              holes.push_back(c);
          }
        for (unsigned int j = 0; j < g.n_pins; ++j)
          pin_centres.push_back(geometry.pin_centre(j));
        // The core circle has 12 segments (transfinite): match them inside.
        core_size =
          2. * dealii::numbers::PI * settings.scene.pin_core_radius / 12.;
        core_radius = settings.scene.pin_core_radius;
      }



      double
      SizeField::operator()(const int    dim,
                            const int    tag,
                            const double x,
                            const double y) const
      {
        // Discs and pins are split once into quadrilaterals after meshing
        // (split_into_quadrilaterals()): gmsh meshes them at twice the size.
        // The housing is structured; its node counts are set directly.
        const double sc = 2.;
        if (dim == 2 && pins.core_surfaces.count(tag))
          return sc * core_size;
        if (pins.entities.count(std::make_pair(dim, tag)))
          {
            // In a pin: graded from the core circle's segments outwards.
            double d_pin = std::numeric_limits<double>::max();
            for (const auto &c : pin_centres)
              d_pin = std::min(d_pin, dealii::Point<2>(x, y).distance(c));
            return sc * std::min(size(x, y), core_size + (d_pin - core_radius));
          }
        return sc * size(x, y);
      }



      double
      SizeField::size(const double x, const double y) const
      {
        const dealii::Point<2> p(x, y);
        // Nearest pin centre: points in a pin or in the housing.
        double d_pin = std::numeric_limits<double>::max();
        for (const auto &c : pin_centres)
          d_pin = std::min(d_pin, p.distance_square(c));
        d_pin = std::sqrt(d_pin);
        if (p.norm() > pin_circle_radius && d_pin > 1.001 * pin_radius)
          // Housing: fine at the grooves only, graded away from them.
          return std::min(m.coarse_size,
                          m.pin_size + m.grading * (d_pin - pin_radius));

        double d = std::numeric_limits<double>::max();
        for (const auto &c : points)
          d = std::min(d, p.distance_square(c));
        d        = std::sqrt(d);
        double h = std::min(m.coarse_size,
                            m.contact_size +
                              m.grading * std::max(0., d - m.fine_radius));
        for (const auto &c : disc_centres)
          if (p.distance(c) > ring_radius)
            h = std::min(h, m.flank_size);
        // Bore and crank holes: 0.15 of the radius (a chord of 8.6 deg).
        for (const auto &c : holes)
          if (std::abs(p.distance(c.centre) - c.radius) < 0.3 * c.radius)
            h = std::min(h, 0.15 * c.radius);
        if (d_pin < 2. * pin_radius)
          h = std::min(h, m.pin_size);
        return h;
      }



      void
      set_size_field_and_options(const SizeField         &field,
                                 const std::vector<Body> &bodies)
      {
        gmsh::model::mesh::setSizeCallback(
          [&field](int dim, int tag, double x, double y, double) {
            return field(dim, tag, x, y);
          });
        gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
        gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
        gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
        // Delaunay + blossom: in our scenes this leaves no triangles (tested
        // over crank angles and scenes); frontal-quad (8) crashes with a
        // size callback in gmsh 4.8.
        gmsh::option::setNumber("Mesh.Algorithm", 5);
        gmsh::option::setNumber("Mesh.RecombinationAlgorithm", 1);
        gmsh::option::setNumber("Mesh.RecombineAll", 1);
        gmsh::option::setNumber("Mesh.Smoothing", 5);
        for (const Body &body : bodies)
          for (const int s : body.surfaces)
            gmsh::model::mesh::setRecombine(2, s);
      }
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid

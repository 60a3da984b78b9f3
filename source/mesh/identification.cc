#include <deal.II/base/exceptions.h>

#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <cycloid/mesh/identification.h>
#include <cycloid/mesh/ids.h>
#include <cycloid/mesh/manifolds.h>

#include <cmath>
#include <string>
#include <vector>

namespace cycloid
{
  namespace mesh
  {
    namespace
    {
      /** |xy distance of p from c| == r within tol for all points. */
      template <int dim>
      bool
      all_on_circle(const std::vector<dealii::Point<dim>> &points,
                    const dealii::Point<2>                &c,
                    const double                           r,
                    const double                           tol)
      {
        for (const auto &p : points)
          if (std::abs(std::hypot(p[0] - c[0], p[1] - c[1]) - r) > tol)
            return false;
        return true;
      }



      /**
       * Boundary and manifold ids of the faces of one body kind each: a
       * face is told apart by the exact circle its vertices lie on, within
       * a tolerance relative to the stage's size.
       */
      template <int dim>
      class FaceIdentifier
      {
      public:
        /** A face of the triangulation. */
        using Face = typename dealii::Triangulation<dim>::face_iterator;
        /** The vertices of a face. */
        using Points = std::vector<dealii::Point<dim>>;

        /** The stage placed at crank angle @p psi. */
        FaceIdentifier(const MeshSettings              &settings,
                       const geometry::CycloidGeometry &geometry,
                       const double                     psi)
          : g(settings.geometry)
          , pin_core_radius(settings.scene.pin_core_radius)
          , geometry(geometry)
          , psi(psi)
          , tol(1e-6 * geometry.pin_circle_radius())
        {}

        /** Identify @p face of a cell of body @p m. */
        void
        identify(const Face &face, const dealii::types::material_id m) const
        {
          Points pts;
          for (const unsigned int v : face->vertex_indices())
            pts.push_back(face->vertex(v));
          if (!face->at_boundary())
            {
              // Interior interface of a pin's core: keep it round.
              if (ids::is_pin(m))
                {
                  const unsigned int j = ids::pin_index(m);
                  if (all_on_circle(
                        pts, geometry.pin_centre(j), pin_core_radius, tol))
                    face->set_all_manifold_ids(ids::pin_core_manifold(j));
                }
              return;
            }
          if (is_axial(pts))
            face->set_boundary_id(ids::axial_faces(m));
          else if (ids::is_disc(m))
            disc_face(face, pts, m);
          else if (ids::is_pin(m))
            pin_face(face, pts, ids::pin_index(m));
          else if (m == ids::housing)
            housing_face(face, pts);
        }

      private:
        /** In 3D: does the face lie in a plane z = const? */
        bool
        is_axial(const Points &pts) const
        {
          if (dim != 3)
            return false;
          bool axial = true;
          for (const auto &p : pts)
            axial = axial && std::abs(p[dim - 1] - pts[0][dim - 1]) < tol;
          return axial;
        }

        /** Disc @p d (not an axial face): bore, crank hole, or else flank. */
        void
        disc_face(const Face        &face,
                  const Points      &pts,
                  const unsigned int d) const
        {
          if (all_on_circle(
                pts, geometry.disc_centre(d, psi), g.bore_radius, tol))
            {
              face->set_boundary_id(ids::bore);
              face->set_all_manifold_ids(ids::bore_manifold(d));
              return;
            }
          for (unsigned int k = 0; k < g.n_crank_holes; ++k)
            {
              const auto h = geometry.crank_hole_centre(d, k, psi);
              if (all_on_circle(pts, h, g.crank_hole_radius, tol))
                {
                  face->set_boundary_id(ids::crank_hole);
                  face->set_all_manifold_ids(ids::crank_hole_manifold(d, k));
                  return;
                }
            }
          face->set_boundary_id(ids::flank);
          face->set_all_manifold_ids(ids::profile_manifold(d));
        }

        /** Pin @p j (not an end face): its cylinder, checked. */
        void
        pin_face(const Face        &face,
                 const Points      &pts,
                 const unsigned int j) const
        {
          AssertThrow(all_on_circle(pts,
                                    geometry.pin_centre(j),
                                    geometry.pin_radius(j),
                                    tol),
                      dealii::ExcMessage("mesh: a boundary face of pin " +
                                         std::to_string(j) +
                                         " is not on the pin's cylinder."));
          face->set_boundary_id(ids::pin_surface);
          face->set_all_manifold_ids(ids::pin_manifold(j));
        }

        /** Housing (not an axial face): outer cylinder, a pin's seat, or
         * else the inner cylinder between the grooves. */
        void
        housing_face(const Face &face, const Points &pts) const
        {
          if (all_on_circle(pts,
                            dealii::Point<2>(),
                            geometry.pin_circle_radius() + g.housing_thickness,
                            tol))
            {
              face->set_boundary_id(ids::housing_outer);
              face->set_all_manifold_ids(ids::housing_manifold);
              return;
            }
          face->set_boundary_id(ids::housing_inner);
          face->set_all_manifold_ids(ids::housing_manifold);
          for (unsigned int j = 0; j < g.n_pins; ++j)
            if (all_on_circle(
                  pts, geometry.pin_centre(j), geometry.pin_radius(j), tol))
              {
                face->set_boundary_id(ids::housing_seat);
                face->set_all_manifold_ids(ids::pin_manifold(j));
                return;
              }
        }

        const geometry::GeometryParameters &g;
        const double                        pin_core_radius;
        const geometry::CycloidGeometry    &geometry;
        const double                        psi;
        const double                        tol;
      };
    } // namespace



    template <int dim>
    void
    internal::identify_boundaries(const MeshSettings              &settings,
                                  const geometry::CycloidGeometry &geometry,
                                  const double                     psi,
                                  dealii::Triangulation<dim>      &tria)
    {
      const FaceIdentifier<dim> identifier(settings, geometry, psi);
      for (const auto &cell : tria.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          identifier.identify(cell->face(f), cell->material_id());
    }



    template <int dim>
    void
    internal::project_boundary_vertices(
      const MeshSettings              &settings,
      const geometry::CycloidGeometry &geometry,
      const double                     psi,
      dealii::Triangulation<dim>      &tria)
    {
      std::vector<CycloidProfileManifold<dim>> profiles;
      for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
        profiles.emplace_back(geometry, d, psi);
      std::vector<bool> moved(tria.n_vertices(), false);
      for (const auto &cell : tria.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          {
            const auto face = cell->face(f);
            if (!face->at_boundary())
              continue;
            const auto b = face->boundary_id();
            for (const unsigned int v : face->vertex_indices())
              {
                const unsigned int index = face->vertex_index(v);
                if (moved[index])
                  continue;
                if (b == ids::flank)
                  {
                    face->vertex(v) =
                      profiles[cell->material_id()].project(face->vertex(v));
                    moved[index] = true;
                  }
                else if (b == ids::pin_surface)
                  {
                    const unsigned int j = ids::pin_index(cell->material_id());
                    face->vertex(v)      = project_to_circle(face->vertex(v),
                                                        geometry.pin_centre(j),
                                                        geometry.pin_radius(j));
                    moved[index]         = true;
                  }
              }
          }
    }



    template void
    internal::identify_boundaries<2>(const MeshSettings &,
                                     const geometry::CycloidGeometry &,
                                     const double,
                                     dealii::Triangulation<2> &);
    template void
    internal::identify_boundaries<3>(const MeshSettings &,
                                     const geometry::CycloidGeometry &,
                                     const double,
                                     dealii::Triangulation<3> &);
    template void
    internal::project_boundary_vertices<2>(const MeshSettings &,
                                           const geometry::CycloidGeometry &,
                                           const double,
                                           dealii::Triangulation<2> &);
    template void
    internal::project_boundary_vertices<3>(const MeshSettings &,
                                           const geometry::CycloidGeometry &,
                                           const double,
                                           dealii::Triangulation<3> &);
  } // namespace mesh
} // namespace cycloid

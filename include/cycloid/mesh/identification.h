#ifndef cycloid_mesh_identification_h
#define cycloid_mesh_identification_h

#include <deal.II/grid/tria.h>

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/mesh/mesh_request.h>

namespace cycloid
{
  namespace mesh
  {
    namespace internal
    {
      /**
       * @brief Set the boundary ids and the manifold ids (mesh::ids) of the
       * faces of @p tria, the stage placed at crank angle @p psi. Decided
       * from the exact geometry, not from gmsh's curves, so that the
       * extruded 3D faces and the turned periodic meshes need no
       * bookkeeping: the nodes gmsh puts on circles are exact, the flank is
       * whatever else a disc has on its boundary. The pins' core circles
       * (interior faces) get the pins' core manifolds, so that they stay
       * round under refinement.
       */
      template <int dim>
      void
      identify_boundaries(const MeshSettings              &settings,
                          const geometry::CycloidGeometry &geometry,
                          const double                     psi,
                          dealii::Triangulation<dim>      &tria);

      /**
       * @brief Move the coarse vertices of the flanks from gmsh's splines
       * onto the exact profile, and those of the pin surfaces onto their
       * cylinders (exact already, but projected to remove round-off).
       * Needs the boundary ids of identify_boundaries().
       */
      template <int dim>
      void
      project_boundary_vertices(const MeshSettings              &settings,
                                const geometry::CycloidGeometry &geometry,
                                const double                     psi,
                                dealii::Triangulation<dim>      &tria);
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid

#endif

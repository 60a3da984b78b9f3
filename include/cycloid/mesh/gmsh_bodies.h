#ifndef cycloid_mesh_gmsh_bodies_h
#define cycloid_mesh_gmsh_bodies_h

#include <deal.II/base/types.h>

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/mesh/circle.h>
#include <cycloid/mesh/mesh_request.h>

#include <set>
#include <utility>
#include <vector>

namespace cycloid
{
  namespace mesh
  {
    namespace internal
    {
      /**
       * @brief A body of the section as gmsh geo-kernel entities: what the
       * extraction of the raw mesh needs to label its cells and to put the
       * split's midpoints onto the exact circles.
       */
      struct Body
      {
        /** Material id of the body (mesh::ids). */
        dealii::types::material_id material;
        /** Its plane surfaces (z = 0). */
        std::vector<int> surfaces;
        /** Its curves that lie on exact circles. */
        std::vector<int> circles;
      };

      /**
       * @brief The gmsh entities of the pins, which the size field grades
       * on their own (from the core circle outwards).
       */
      struct PinEntities
      {
        /** Curves and surfaces of every pin: (dim, tag). */
        std::set<std::pair<int, int>> entities;
        /** Surfaces of the pins' cores. */
        std::set<int> core_surfaces;
      };

      /**
       * @brief Add the bodies of the scene to the current gmsh model, in
       * the order discs, pins, housing (if Scene/Pin support = housing),
       * and collect the pins' entities into @p pins. The order fixes gmsh's
       * entity and node numbering, hence the mesh: keep it.
       */
      std::vector<Body>
      add_bodies(const MeshSettings              &settings,
                 const geometry::CycloidGeometry &geometry,
                 const double                     psi,
                 PinEntities                     &pins);

      /**
       * @brief The exact circles of body @p m: a disc's bore and crank
       * holes, a pin's surface and core, the housing's inner and outer
       * circle and seats.
       */
      std::vector<Circle>
      circles_of(const MeshSettings              &settings,
                 const geometry::CycloidGeometry &geometry,
                 const double                     psi,
                 const dealii::types::material_id m);
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid

#endif

#ifndef cycloid_mesh_extrusion_h
#define cycloid_mesh_extrusion_h

#include <deal.II/grid/tria.h>

#include <cycloid/mesh/mesh_request.h>
#include <cycloid/mesh/raw_mesh.h>

#include <utility>

namespace cycloid
{
  namespace mesh
  {
    /**
     * @brief Axial extent [z0, z1] of disc @p d in a 3D scene: discs of
     * width b, the second one after an axial gap (mm).
     */
    std::pair<double, double>
    disc_axial_range(const MeshSettings &settings, const unsigned int d);

    namespace internal
    {
      /**
       * @brief Create @p tria (empty) from the meshed section @p raw:
       * in 2D the section's quadrilaterals themselves, in 3D the section
       * extruded into hexahedra, a disc through its width
       * (disc_axial_range()), the pins and the housing through both discs
       * and the gap, with layers that match at the discs' faces. The cells
       * keep the section's material ids; boundary and manifold ids are
       * left to identify_boundaries().
       */
      template <int dim>
      void
      create_from_section(const MeshSettings         &settings,
                          const RawMesh              &raw,
                          dealii::Triangulation<dim> &tria);
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid

#endif

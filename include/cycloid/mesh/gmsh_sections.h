#ifndef cycloid_mesh_gmsh_sections_h
#define cycloid_mesh_gmsh_sections_h

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/mesh/mesh_request.h>
#include <cycloid/mesh/raw_mesh.h>

#include <string>

namespace cycloid
{
  namespace mesh
  {
    namespace internal
    {
      /**
       * @brief Mesh the section of the scene at crank angle @p psi (z = 0)
       * with the gmsh C++ API: quadrilaterals only, the discs and pins
       * split once into quadrilaterals, the housing structured. The size
       * field is fine at the contact points of crank angles psi ... psi +
       * @p sweep. Writes the gmsh model to @p msh_file unless it is empty.
       * Runs gmsh from initialize() to finalize(): call it on one rank.
       */
      RawMesh
      generate_sections(const MeshSettings              &settings,
                        const geometry::CycloidGeometry &geometry,
                        const double                     psi,
                        const std::string               &msh_file,
                        const double                     sweep);
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid

#endif

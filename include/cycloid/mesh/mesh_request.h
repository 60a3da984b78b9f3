#ifndef cycloid_mesh_mesh_request_h
#define cycloid_mesh_mesh_request_h

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/mesh/mesh_parameters.h>
#include <cycloid/parameters/scene.h>

#include <string>
#include <vector>

namespace cycloid
{
  namespace mesh
  {
    /**
     * @brief What a run asks of the mesh. The parameter file fixes the
     * scene (MeshSettings); a run decides where the crank stands, which
     * way it is loaded and where the gmsh model goes, and says it here, so
     * that the mesh layer needs no run, loading or output parameters.
     */
    struct MeshRequest
    {
      /** Crank angle of the discs' placement [rad]. */
      double crank_angle = 0;
      /** The contact size and refinement cover crank angles crank_angle
       * ... crank_angle + sweep [rad] (transient runs). */
      double sweep = 0;
      /** Sign of the run's loads, for `Mesh/Contact refinement side =
       * loaded`: +1, -1, or 0 (loads of both signs: every pin). Used only
       * when MeshParameters::refine_loaded_side_only. */
      int load_sign = 0;
      /** Write the gmsh model to this file if not empty (Mesh/Write msh
       * file). */
      std::string msh_file;
    };

    /**
     * @brief The common sign of @p loads: +1 if all >= 0, -1 if all <= 0,
     * else 0 (also 0 if all are zero or there are none: no side is loaded
     * more than the other, so every pin is refined).
     */
    int
    common_sign(const std::vector<double> &loads);

    /**
     * @brief Everything the mesh reads from the parameter file: the
     * geometry of the stage, the scene (how many discs, what holds the
     * pins) and the element sizes.
     */
    struct MeshSettings
    {
      /** Subsection `Geometry`. */
      geometry::GeometryParameters geometry;
      /** Subsection `Scene`. */
      parameters::SceneParameters scene;
      /** Subsection `Mesh`. */
      MeshParameters mesh;
    };
  } // namespace mesh
} // namespace cycloid

#endif

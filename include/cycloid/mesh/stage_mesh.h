#ifndef cycloid_mesh_stage_mesh_h
#define cycloid_mesh_stage_mesh_h

#include <deal.II/distributed/tria_base.h>
#include <deal.II/grid/tria.h>

#include <cycloid/mesh/contact_refinement.h>
#include <cycloid/mesh/extrusion.h>
#include <cycloid/mesh/ids.h>
#include <cycloid/mesh/manifolds.h>
#include <cycloid/mesh/mesh_request.h>
#include <cycloid/mesh/mesh_statistics.h>

#include <memory>

namespace cycloid
{
  namespace mesh
  {
    /**
     * @brief Generate the mesh of the scene with the gmsh C++ API (on rank 0
     * of @p tria's communicator, broadcast to the others), create @p tria
     * with material and boundary ids, move the coarse boundary vertices onto
     * the exact curves and attach the exact manifolds (cycloid profile, pin
     * and hole cylinders), then apply the settings' global and contact
     * refinements. @p tria must be empty.
     *
     * The discs are placed at @p request's crank angle; with a sweep != 0
     * the contact size and refinement cover the contact points of crank
     * angles crank_angle ... crank_angle + sweep (transient runs, whose
     * discs follow the crank).
     *
     * 2D: one section at z = 0 (plane strain), quadrilaterals. 3D: the
     * sections extruded through the disc widths into hexahedra, the discs
     * axially apart by `Geometry/Axial gap between discs`, the pins (and
     * housing) spanning both discs.
     */
    template <int dim>
    void
    create_stage_mesh(const MeshSettings         &settings,
                      const MeshRequest          &request,
                      dealii::Triangulation<dim> &tria);

    /**
     * @brief An empty triangulation on @p comm as `Mesh/Triangulation` asks:
     * parallel::shared::Triangulation partitioned by METIS (every rank holds
     * every cell), or parallel::distributed::Triangulation (p4est: the
     * coarse grid on every rank, each refined cell on one rank and a ghost
     * layer). Both smooth the levels at vertices (2:1 across vertices, as
     * p4est balances).
     */
    template <int dim>
    std::unique_ptr<dealii::parallel::TriangulationBase<dim>>
    create_triangulation(const MeshParameters &settings, const MPI_Comm comm);
  } // namespace mesh
} // namespace cycloid

#endif

#ifndef cycloid_mesh_stage_mesh_h
#define cycloid_mesh_stage_mesh_h

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <deal.II/grid/tria.h>

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/mesh/ids.h>
#include <cycloid/mesh/mesh_request.h>

#include <string>
#include <vector>

namespace cycloid
{
  namespace mesh
  {
    /**
     * @brief The stage's contact points at a crank angle: the closest point
     * of every disc to every pin (housing frame, mm). They drive the mesh
     * size field and the a-priori refinement.
     */
    std::vector<dealii::Point<2>>
    contact_points(const geometry::CycloidGeometry &geometry,
                   const unsigned int               n_discs,
                   const double                     psi);

    /**
     * @brief The contact points met while the crank turns from @p psi to
     * @p psi + @p sweep [rad], for a mesh placed at @p psi: the pins' points
     * (housing frame) and the discs' material points carried back to their
     * placement at @p psi, sampled every 1/20 of a mesh period. With
     * @p sweep = 0 the points of contact_points(). With @p load_sign = +1
     * or -1 only the contacts whose moment arm resists a load of that sign
     * (arm x load_sign >= -5 % of the largest arm), with 0 all of them.
     */
    std::vector<dealii::Point<2>>
    contact_points_along(const geometry::CycloidGeometry &geometry,
                         const unsigned int               n_discs,
                         const double                     psi,
                         const double                     sweep,
                         const int                        load_sign = 0);

    /**
     * @brief Axial extent [z0, z1] of disc @p d in a 3D scene: discs of
     * width b, the second one after an axial gap (mm).
     */
    std::pair<double, double>
    disc_axial_range(const MeshSettings &settings, const unsigned int d);

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
     * @brief Attach the exact manifolds of the scene to @p tria's manifold
     * ids (also needed after loading a triangulation).
     */
    template <int dim>
    void
    attach_manifolds(const MeshSettings         &settings,
                     const double                psi,
                     dealii::Triangulation<dim> &tria);

    /**
     * @brief Refine the cells within @p radius of a contact point
     * @p n_cycles times.
     */
    template <int dim>
    void
    refine_near_contacts(const std::vector<dealii::Point<2>> &points,
                         const double                         radius,
                         const unsigned int                   n_cycles,
                         dealii::Triangulation<dim>          &tria);

    /**
     * @brief Per-body statistics of a mesh (collective over the
     * triangulation's communicator).
     */
    struct BodyStatistics
    {
      dealii::types::material_id material_id;
      unsigned int               n_cells    = 0;
      unsigned int               n_vertices = 0;
      /** Area (2D) or volume (3D) of the Q1 cells [mm^2 or mm^3]. */
      double measure = 0;
      /** Smallest scaled Jacobian over the cells' vertices (1: square). */
      double min_scaled_jacobian = 1;
      /** Centre of the cell with the smallest scaled Jacobian [mm]. */
      dealii::Point<3> worst_cell;
      /** Largest ratio of longest to shortest edge of a cell. */
      double max_aspect_ratio = 1;
    };

    /** Statistics per body, ordered by material id. */
    template <int dim>
    std::vector<BodyStatistics>
    body_statistics(const dealii::Triangulation<dim> &tria);
  } // namespace mesh
} // namespace cycloid

#endif

#ifndef cycloid_mesh_mesh_statistics_h
#define cycloid_mesh_mesh_statistics_h

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <deal.II/grid/tria.h>

#include <vector>

namespace cycloid
{
  namespace mesh
  {
    /**
     * @brief Per-body statistics of a mesh: size and quality of each body,
     * so that a run can tell which body a bad cell is in.
     */
    struct BodyStatistics
    {
      /** The body (mesh::ids). */
      dealii::types::material_id material_id;
      /** Number of active cells. */
      unsigned int n_cells = 0;
      /** Number of vertices of those cells. */
      unsigned int n_vertices = 0;
      /** Area (2D) or volume (3D) of the Q1 cells [mm^2 or mm^3]. */
      double measure = 0;
      /** Smallest scaled Jacobian over the cells' vertices (1: square). */
      double min_scaled_jacobian = 1;
      /** Centre of the cell with the smallest scaled Jacobian [mm]. */
      dealii::Point<3> worst_cell;
      /** Largest ratio of longest to shortest edge of a cell. */
      double max_aspect_ratio = 1;
    };

    /** Statistics per body of @p tria's active cells, ordered by material
     * id. */
    template <int dim>
    std::vector<BodyStatistics>
    body_statistics(const dealii::Triangulation<dim> &tria);
  } // namespace mesh
} // namespace cycloid

#endif

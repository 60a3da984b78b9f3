#ifndef cycloid_mesh_contact_refinement_h
#define cycloid_mesh_contact_refinement_h

#include <deal.II/base/point.h>

#include <deal.II/grid/tria.h>

#include <cycloid/geometry/cycloid_geometry.h>

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
     * @brief Refine the cells within @p radius of a contact point
     * @p n_cycles times (distances in the section plane, so that in 3D the
     * refinement runs through the whole width).
     */
    template <int dim>
    void
    refine_near_contacts(const std::vector<dealii::Point<2>> &points,
                         const double                         radius,
                         const unsigned int                   n_cycles,
                         dealii::Triangulation<dim>          &tria);

    /**
     * @brief Whether @p cell is within two of its own sizes of the contact
     * node @p p: the rule of the adaptive refinement at the active nodes.
     *
     * In 2D the distance from the cell's centre is below twice the cell's
     * diameter. In 3D the cell's size is measured in the section plane
     * (twice the largest distance of a vertex from the centre in x, y), and
     * @p p must lie in the cell's axial span widened by twice that size:
     * the 3D meshes are extruded, with cells as long as a disc is wide, so
     * the 3D diameter would reach across half the disc and refine nearly
     * every cell of a loaded disc (233 k of 370 k cells on the 3D seed
     * case, doc/error-estimate.md).
     */
    template <int dim>
    bool
    near_contact_node(
      const typename dealii::Triangulation<dim>::active_cell_iterator &cell,
      const dealii::Point<dim>                                        &p);
  } // namespace mesh
} // namespace cycloid

#endif

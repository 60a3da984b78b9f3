#ifndef cycloid_mesh_manifolds_h
#define cycloid_mesh_manifolds_h

#include <deal.II/grid/manifold.h>
#include <deal.II/grid/tria.h>

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/mesh/mesh_request.h>

#include <memory>

namespace cycloid
{
  namespace mesh
  {
    /**
     * @brief The exact (modified) cycloid profile of one placed disc as a
     * deal.II manifold: a curve in 2D (chart: the profile parameter phi), a
     * cylindrical surface along z in 3D (chart: phi, z). New vertices on
     * the tooth flanks land on the true profile at every refinement.
     *
     * pull_back() uses the geometry's closest-point search, push_forward()
     * the closed-form profile, and the chart's phi is periodic with period
     * 2 pi zc.
     */
    template <int dim>
    class CycloidProfileManifold
      : public dealii::ChartManifold<dim, dim, dim - 1>
    {
    public:
      /** Profile of disc @p disc at crank angle @p psi. */
      CycloidProfileManifold(const geometry::CycloidGeometry &geometry,
                             const unsigned int               disc,
                             const double                     psi);

      /** A copy (deal.II's manifold interface). */
      std::unique_ptr<dealii::Manifold<dim, dim>>
      clone() const override;

      /** Chart coordinates (profile parameter, and z in 3D) of
       * @p space_point. */
      dealii::Point<dim - 1>
      pull_back(const dealii::Point<dim> &space_point) const override;

      /** The point of the profile surface at @p chart_point. */
      dealii::Point<dim>
      push_forward(const dealii::Point<dim - 1> &chart_point) const override;

      /** Closest point of the profile surface to @p p (same z in 3D). */
      dealii::Point<dim>
      project(const dealii::Point<dim> &p) const;

    private:
      const geometry::CycloidGeometry geometry;
      const unsigned int              disc;
      const double                    psi;
      const double                    period;
    };

    /**
     * @brief A circle in 2D or a cylinder along z in 3D through
     * @p centre: PolarManifold or CylindricalManifold.
     */
    template <int dim>
    std::unique_ptr<dealii::Manifold<dim, dim>>
    make_circle_manifold(const dealii::Point<2> &centre);

    /** Radial projection of @p p onto the circle (cylinder) of radius
     * @p radius about @p centre. */
    template <int dim>
    dealii::Point<dim>
    project_to_circle(const dealii::Point<dim> &p,
                      const dealii::Point<2>   &centre,
                      const double              radius);

    /**
     * @brief Attach the exact manifolds of the scene placed at crank angle
     * @p psi to @p tria's manifold ids (mesh::ids): the discs' profiles,
     * bores and crank holes, the pins' cylinders and cores, the housing.
     * create_stage_mesh() calls it; call it again after loading a
     * triangulation, which keeps the ids but not the manifolds.
     */
    template <int dim>
    void
    attach_manifolds(const MeshSettings         &settings,
                     const double                psi,
                     dealii::Triangulation<dim> &tria);
  } // namespace mesh
} // namespace cycloid

#endif

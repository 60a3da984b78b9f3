#ifndef cycloid_mesh_stage_mesh_h
#define cycloid_mesh_stage_mesh_h

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <deal.II/grid/tria.h>

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/parameters/all_parameters.h>

#include <string>
#include <vector>

namespace cycloid
{
  namespace mesh
  {
    /**
     * @brief Identifiers of bodies, surfaces and manifolds in the stage
     * mesh.
     *
     * | material_id | body          |
     * |-------------|---------------|
     * | 0, 1        | disc 0, disc 1|
     * | 9           | housing       |
     * | 100 + j     | pin j         |
     *
     * | boundary_id | surface                                        |
     * |-------------|------------------------------------------------|
     * | 1           | tooth flank (cycloid profile)                  |
     * | 2           | disc bore                                      |
     * | 3           | crank holes                                    |
     * | 4           | pin surface                                    |
     * | 5           | housing seat (pin grooves)                     |
     * | 6           | housing outer surface                          |
     * | 7           | housing inner surface between the grooves      |
     * | 8           | disc axial faces (3D)                          |
     * | 9           | pin end faces (3D)                             |
     * | 10          | housing axial faces (3D)                       |
     */
    namespace ids
    {
      /** Material id of disc @p d. */
      constexpr dealii::types::material_id
      disc(const unsigned int d)
      {
        return d;
      }
      /** Material id of the housing. */
      constexpr dealii::types::material_id housing = 9;
      /** Material id of pin @p j. */
      constexpr dealii::types::material_id
      pin(const unsigned int j)
      {
        return 100 + j;
      }
      /** Is @p m a pin's material id? */
      constexpr bool
      is_pin(const dealii::types::material_id m)
      {
        return m >= 100 && m != dealii::numbers::invalid_material_id;
      }

      constexpr dealii::types::boundary_id flank         = 1;
      constexpr dealii::types::boundary_id bore          = 2;
      constexpr dealii::types::boundary_id crank_hole    = 3;
      constexpr dealii::types::boundary_id pin_surface   = 4;
      constexpr dealii::types::boundary_id housing_seat  = 5;
      constexpr dealii::types::boundary_id housing_outer = 6;
      constexpr dealii::types::boundary_id housing_inner = 7;
      constexpr dealii::types::boundary_id disc_axial    = 8;
      constexpr dealii::types::boundary_id pin_axial     = 9;
      constexpr dealii::types::boundary_id housing_axial = 10;

      /** Name of a boundary id, for output. */
      std::string
      boundary_name(const dealii::types::boundary_id b);
      /** Name of a body, for output. */
      std::string
      body_name(const dealii::types::material_id m);

      /** Manifold id of the profile of disc @p d. */
      constexpr dealii::types::manifold_id
      profile_manifold(const unsigned int d)
      {
        return 1 + d;
      }
      /** Manifold id of the bore of disc @p d. */
      constexpr dealii::types::manifold_id
      bore_manifold(const unsigned int d)
      {
        return 3 + d;
      }
      /** Manifold id of the housing's outer cylinder. */
      constexpr dealii::types::manifold_id housing_manifold = 5;
      /** Manifold id of crank hole @p k of disc @p d. */
      constexpr dealii::types::manifold_id
      crank_hole_manifold(const unsigned int d, const unsigned int k)
      {
        return 10 + 20 * d + k;
      }
      /** Manifold id of pin @p j's cylinder (pin surface and its groove). */
      constexpr dealii::types::manifold_id
      pin_manifold(const unsigned int j)
      {
        return 100 + j;
      }
      /** Manifold id of pin @p j's core circle (interior interface). */
      constexpr dealii::types::manifold_id
      pin_core_manifold(const unsigned int j)
      {
        return 2000 + j;
      }
    } // namespace ids

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
    disc_axial_range(const parameters::AllParameters &prm,
                     const unsigned int               d);

    /**
     * @brief Generate the mesh of the scene with the gmsh C++ API (on rank 0
     * of @p tria's communicator, broadcast to the others), create @p tria
     * with material and boundary ids, move the coarse boundary vertices onto
     * the exact curves and attach the exact manifolds (cycloid profile, pin
     * and hole cylinders), then apply the prm's global and contact
     * refinements. @p tria must be empty. With @p sweep != 0 [rad] the
     * contact size and refinement cover the contact points of crank angles
     * psi ... psi + sweep (transient runs, whose discs follow the crank).
     *
     * 2D: one section at z = 0 (plane strain), quadrilaterals. 3D: the
     * sections extruded through the disc widths into hexahedra, the discs
     * axially apart by `Geometry/Axial gap between discs`, the pins (and
     * housing) spanning both discs.
     */
    template <int dim>
    void
    create_stage_mesh(const parameters::AllParameters &prm,
                      const double                     psi,
                      dealii::Triangulation<dim>      &tria,
                      const double                     sweep = 0.);

    /**
     * @brief Attach the exact manifolds of the scene to @p tria's manifold
     * ids (also needed after loading a triangulation).
     */
    template <int dim>
    void
    attach_manifolds(const parameters::AllParameters &prm,
                     const double                     psi,
                     dealii::Triangulation<dim>      &tria);

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

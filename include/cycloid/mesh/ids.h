#ifndef cycloid_mesh_ids_h
#define cycloid_mesh_ids_h

#include <deal.II/base/types.h>

#include <string>

namespace cycloid
{
  namespace mesh
  {
    /**
     * @brief Identifiers of bodies, surfaces and manifolds in the stage
     * mesh. Everything that asks "which body, which surface" goes through
     * these helpers, so that the numbering below is written down once.
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
      /** Most discs a stage has (an RV stage: two, half a turn apart). */
      constexpr unsigned int max_discs = 2;

      /** Material id of disc @p d. */
      constexpr dealii::types::material_id
      disc(const unsigned int d)
      {
        return d;
      }
      /** Is @p m a disc's material id? */
      constexpr bool
      is_disc(const dealii::types::material_id m)
      {
        return m < max_discs;
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
        return m >= pin(0) && m != dealii::numbers::invalid_material_id;
      }
      /** Index j of the pin whose material id is @p m (is_pin(m)). */
      constexpr unsigned int
      pin_index(const dealii::types::material_id m)
      {
        return m - pin(0);
      }

      constexpr dealii::types::boundary_id flank =
        1; ///< Cycloid tooth flanks (the contact slave surface).
      constexpr dealii::types::boundary_id bore =
        2; ///< Central bore of a disc.
      constexpr dealii::types::boundary_id crank_hole =
        3; ///< Crank (eccentric bearing) holes of a disc.
      constexpr dealii::types::boundary_id pin_surface =
        4; ///< Pin surfaces (the contact masters).
      constexpr dealii::types::boundary_id housing_seat =
        5; ///< Housing grooves that hold the pins.
      constexpr dealii::types::boundary_id housing_outer =
        6; ///< Outer surface of the housing (held).
      constexpr dealii::types::boundary_id housing_inner =
        7; ///< Free inner surface of the housing between the seats.
      constexpr dealii::types::boundary_id disc_axial =
        8; ///< End faces of a disc (3D).
      constexpr dealii::types::boundary_id pin_axial =
        9; ///< End faces of a pin (3D).
      constexpr dealii::types::boundary_id housing_axial =
        10; ///< End faces of the housing (3D).

      /** Boundary id of the axial (end) faces of body @p m, a disc, a pin
       * or the housing (3D). */
      constexpr dealii::types::boundary_id
      axial_faces(const dealii::types::material_id m)
      {
        return is_disc(m) ? disc_axial : is_pin(m) ? pin_axial : housing_axial;
      }

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
  }   // namespace mesh
} // namespace cycloid

#endif

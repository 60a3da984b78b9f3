#ifndef cycloid_mesh_size_field_h
#define cycloid_mesh_size_field_h

#include <deal.II/base/point.h>

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/mesh/circle.h>
#include <cycloid/mesh/gmsh_bodies.h>
#include <cycloid/mesh/mesh_request.h>

#include <set>
#include <utility>
#include <vector>

namespace cycloid
{
  namespace mesh
  {
    namespace internal
    {
      /**
       * @brief The element size field of the section (see MeshParameters):
       * graded from the contact points, bounded along the flanks, the holes
       * and in the pins, and graded from the grooves in the housing. gmsh
       * asks it for the size at every point it meshes (a size callback),
       * so that no background mesh is needed.
       */
      class SizeField
      {
      public:
        /**
         * The field of the scene at crank angle @p psi, fine at the contact
         * points of crank angles psi ... psi + @p sweep; @p pins are the
         * entities graded from the pins' cores. Keeps a reference to
         * @p settings.
         */
        SizeField(const MeshSettings              &settings,
                  const geometry::CycloidGeometry &geometry,
                  const double                     psi,
                  const double                     sweep,
                  const PinEntities               &pins);

        /** The size gmsh uses at (@p x, @p y) on entity (@p dim, @p tag). */
        double
        operator()(const int    dim,
                   const int    tag,
                   const double x,
                   const double y) const;

      private:
        /** The design size at (@p x, @p y), before the pins' grading and
         * the split's factor. */
        double
        size(const double x, const double y) const;

        const MeshParameters         &m;
        std::vector<dealii::Point<2>> points;
        std::vector<dealii::Point<2>> disc_centres;
        double                        ring_radius = 0; // toothed ring starts
        std::vector<dealii::Point<2>> pin_centres;
        double                        pin_radius        = 0;
        double                        pin_circle_radius = 0;
        std::vector<Circle>           holes;
        PinEntities                   pins;
        /** Size in the pin cores and radius of the cores. */
        double core_size   = 0;
        double core_radius = 0;
      };

      /**
       * @brief Make gmsh use @p field (which must outlive the meshing) and
       * set the meshing options: Delaunay with blossom recombination into
       * quadrilaterals on every surface of @p bodies.
       */
      void
      set_size_field_and_options(const SizeField         &field,
                                 const std::vector<Body> &bodies);
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid

#endif

#ifndef cycloid_mesh_quad_split_h
#define cycloid_mesh_quad_split_h

#include <cycloid/mesh/circle.h>

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
       * @brief Split every element (triangle or quadrilateral, node indices
       * into @p coordinates, 3 per node) once into quadrilaterals: edge
       * midpoints and the centroid become new nodes. Edges shared by two
       * elements get one midpoint, so the result is conforming; the midpoint
       * of an edge in @p on_circle (a segment of a curve on one of
       * @p circles) is moved onto that circle.
       *
       * Why: gmsh's blossom recombination leaves a few triangles where the
       * parity or shape of a surface asks for them, and where it does
       * changes with the crank angle. Splitting every element gives
       * quadrilaterals only, deterministically.
       */
      std::vector<std::vector<unsigned int>>
      split_into_quadrilaterals(
        const std::vector<std::vector<unsigned int>>          &elements,
        std::vector<double>                                   &coordinates,
        const std::vector<Circle>                             &circles,
        const std::set<std::pair<unsigned int, unsigned int>> &on_circle);
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid

#endif

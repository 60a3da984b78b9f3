#ifndef cycloid_mesh_circle_h
#define cycloid_mesh_circle_h

#include <deal.II/base/point.h>

namespace cycloid
{
  namespace mesh
  {
    namespace internal
    {
      /**
       * @brief A circle of the stage's geometry in the section plane
       * (bore, crank hole, pin, pin core, housing): the curves on which the
       * mesh generator must put new nodes exactly, and near which the size
       * field is fine.
       */
      struct Circle
      {
        /** Centre in the housing frame [mm]. */
        dealii::Point<2> centre;
        /** Radius [mm]. */
        double radius;
      };
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid

#endif

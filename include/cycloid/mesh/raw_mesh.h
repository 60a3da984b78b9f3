#ifndef cycloid_mesh_raw_mesh_h
#define cycloid_mesh_raw_mesh_h

#include <vector>

#include <mpi.h>

namespace cycloid
{
  namespace mesh
  {
    namespace internal
    {
      /**
       * @brief The meshed section of the stage (z = 0) as plain arrays:
       * quadrilaterals and vertices in the order the generator made them.
       * Plain arrays, so that rank 0 alone runs gmsh and broadcasts the
       * result, and so that extrusion needs nothing of gmsh.
       */
      struct RawMesh
      {
        /** Vertex coordinates, 3 per vertex (z = 0). */
        std::vector<double> coordinates;
        /** Vertex indices, 4 per quadrilateral, in gmsh's (counter-)
         * clockwise order. */
        std::vector<unsigned int> cells;
        /** Material id of each cell (mesh::ids). */
        std::vector<unsigned int> materials;
      };

      /** Broadcast @p raw from rank 0 of @p comm to the other ranks. */
      void
      broadcast(RawMesh &raw, const MPI_Comm comm);

      /**
       * @brief Turn @p raw by @p k_pitch pin pitches about the stage axis
       * and relabel the pins accordingly (pin j becomes pin j + k_pitch):
       * the section of a periodic scene at psi + k 2 pi/zp from the one at
       * psi.
       */
      void
      turn_by_pitches(RawMesh           &raw,
                      const unsigned int k_pitch,
                      const unsigned int n_pins);
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid

#endif

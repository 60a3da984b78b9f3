#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>

#include <cycloid/mesh/ids.h>
#include <cycloid/mesh/raw_mesh.h>

#include <cmath>

namespace cycloid
{
  namespace mesh
  {
    namespace internal
    {
      void
      broadcast(RawMesh &raw, const MPI_Comm comm)
      {
        if (dealii::Utilities::MPI::n_mpi_processes(comm) == 1)
          return;
        unsigned long sizes[3] = {raw.coordinates.size(),
                                  raw.cells.size(),
                                  raw.materials.size()};
        MPI_Bcast(sizes, 3, MPI_UNSIGNED_LONG, 0, comm);
        raw.coordinates.resize(sizes[0]);
        raw.cells.resize(sizes[1]);
        raw.materials.resize(sizes[2]);
        MPI_Bcast(raw.coordinates.data(), sizes[0], MPI_DOUBLE, 0, comm);
        MPI_Bcast(raw.cells.data(), sizes[1], MPI_UNSIGNED, 0, comm);
        MPI_Bcast(raw.materials.data(), sizes[2], MPI_UNSIGNED, 0, comm);
      }



      void
      turn_by_pitches(RawMesh           &raw,
                      const unsigned int k_pitch,
                      const unsigned int n_pins)
      {
        const double angle = k_pitch * 2. * dealii::numbers::PI / n_pins;
        const double c = std::cos(angle), s = std::sin(angle);
        for (std::size_t v = 0; v < raw.coordinates.size() / 3; ++v)
          {
            const double x             = raw.coordinates[3 * v],
                         y             = raw.coordinates[3 * v + 1];
            raw.coordinates[3 * v]     = c * x - s * y;
            raw.coordinates[3 * v + 1] = s * x + c * y;
          }
        for (auto &m : raw.materials)
          if (ids::is_pin(m))
            m = ids::pin((ids::pin_index(m) + k_pitch) % n_pins);
      }
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid

#ifndef cycloid_postprocess_mesh_output_h
#define cycloid_postprocess_mesh_output_h

#include <deal.II/grid/tria.h>

#include <string>

#include <mpi.h>

namespace cycloid
{
  namespace postprocess
  {
    /**
     * @brief Write the locally owned cells of @p tria as
     * `<directory>/<name>-<rank>.vtu` with cell data `body_id` (material
     * id), `mpi_rank` and `level`, and the boundary faces as
     * `<name>_boundary-<rank>.vtu` with `boundary_id`, `body_id` and
     * `mpi_rank`; rank 0 writes the `.pvtu` records `<name>.pvtu` and
     * `<name>_boundary.pvtu`. Cell data, so that a VTK reader sees one value
     * per cell or face. Collective.
     */
    template <int dim>
    void
    write_mesh_vtu(const dealii::Triangulation<dim> &tria,
                   const std::string                &directory,
                   const std::string                &name,
                   const MPI_Comm                    comm);
  } // namespace postprocess
} // namespace cycloid

#endif

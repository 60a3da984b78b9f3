#ifndef cycloid_runs_mesh_run_h
#define cycloid_runs_mesh_run_h

#include <cycloid/mesh/stage_mesh.h>

#include <string>

#include <mpi.h>

namespace cycloid
{
  namespace runs
  {
    /**
     * @brief `Run = mesh`: generate the scene's mesh (Scene/Dimension),
     * write it as mesh.pvtu / mesh_boundary.pvtu with body, boundary and
     * rank ids and mesh.csv with cell counts and quality per body, print a
     * summary, and fail on inverted cells.
     */
    template <int dim>
    class MeshRun
    {
    public:
      /** What the run reads from the parameter file. */
      struct Settings
      {
        mesh::MeshSettings mesh;                 ///< The scene to mesh.
        mesh::MeshRequest  request;              ///< Placement and loaded side.
        std::string output_directory = "output"; ///< Where the mesh files go.
      };

      /** Nothing is built before run(): the output directory must exist
       * while the mesh is made (Mesh/Write msh file). */
      MeshRun(const Settings &settings, const MPI_Comm comm);

      /** Mesh, write and check. */
      void
      run();

    private:
      const Settings settings;
      const MPI_Comm comm;
    };
  } // namespace runs
} // namespace cycloid

#endif

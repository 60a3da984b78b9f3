#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/distributed/tria_base.h>

#include <cycloid/mesh/gmsh_sections.h>
#include <cycloid/mesh/identification.h>
#include <cycloid/mesh/raw_mesh.h>
#include <cycloid/mesh/stage_mesh.h>

#include <cmath>

namespace cycloid
{
  namespace mesh
  {
    namespace
    {
      /** The communicator of a parallel triangulation, MPI_COMM_SELF for a
       * serial one: who generates the mesh and who receives it. */
      template <int dim>
      MPI_Comm
      communicator_of(const dealii::Triangulation<dim> &tria)
      {
        if (const auto *p =
              dynamic_cast<const dealii::parallel::TriangulationBase<dim> *>(
                &tria))
          return p->get_communicator();
        return MPI_COMM_SELF;
      }



      /** Where a periodic scene is meshed: the crank angle of the gmsh
       * section and the pin pitches it is then turned by. */
      struct PeriodicPlacement
      {
        /** Crank angle the section is meshed at [rad]. */
        double psi_mesh;
        /** Pin pitches to turn the section by (0 ... zp - 1). */
        unsigned int k_pitch;
      };



      /**
       * Periodic meshes: the stage at psi + 2 pi/zp is the stage at psi
       * turned by one pin pitch (the discs by one extra tooth pitch), when
       * no crank holes break the discs' symmetry. Mesh psi' = psi mod
       * 2 pi/zp and turn the mesh by k pitches, relabelling the pins, so
       * that states a whole number of periods apart have identical meshes.
       * Not with manufacturing deviations.
       */
      PeriodicPlacement
      periodic_placement(const MeshSettings              &settings,
                         const geometry::CycloidGeometry &geometry,
                         const double                     psi)
      {
        const auto       &g = settings.geometry;
        PeriodicPlacement placement{psi, 0};
        // Manufacturing deviations make every pin and disc its own: a
        // stage turned by a pitch is then another stage.
        const bool deviated =
          !g.pin_deviations.empty() || !g.disc_deviations.empty();
        if (settings.mesh.periodic && g.n_crank_holes == 0 && !deviated)
          {
            const double period = geometry.mesh_period();
            const double k      = std::floor(psi / period + 1e-9);
            placement.psi_mesh  = psi - k * period;
            placement.k_pitch   = static_cast<unsigned int>(
              ((static_cast<long>(k) % static_cast<long>(g.n_pins)) +
               g.n_pins) %
              g.n_pins);
          }
        return placement;
      }
    } // namespace



    template <int dim>
    void
    create_stage_mesh(const MeshSettings         &settings,
                      const MeshRequest          &request,
                      dealii::Triangulation<dim> &tria)
    {
      AssertThrow(tria.n_cells() == 0,
                  dealii::ExcMessage("need an empty mesh"));
      AssertThrow(dim == 3 || settings.scene.n_discs == 1,
                  dealii::ExcMessage(
                    "Scene: a 2D (plane-strain) FE scene models one disc; set "
                    "Scene/Number of discs = 1 or auto (the default, which is "
                    "1 in a 2D FE run; forces and K are for that disc), or "
                    "Scene/Dimension = 3 for the two-disc stage."));
      const MPI_Comm                  comm = communicator_of(tria);
      const geometry::CycloidGeometry geo(settings.geometry);
      const double                    psi = request.crank_angle;

      const PeriodicPlacement placement =
        periodic_placement(settings, geo, psi);
      internal::RawMesh raw;
      if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        raw = internal::generate_sections(
          settings, geo, placement.psi_mesh, request.msh_file, request.sweep);
      internal::broadcast(raw, comm);
      if (placement.k_pitch > 0)
        internal::turn_by_pitches(raw,
                                  placement.k_pitch,
                                  settings.geometry.n_pins);

      // From here on the mesh is the stage at psi itself.
      internal::create_from_section(settings, raw, tria);
      internal::identify_boundaries(settings, geo, psi, tria);
      internal::project_boundary_vertices(settings, geo, psi, tria);
      attach_manifolds(settings, psi, tria);

      if (settings.mesh.global_refinements > 0)
        tria.refine_global(settings.mesh.global_refinements);
      const int load_sign =
        settings.mesh.refine_loaded_side_only ? request.load_sign : 0;
      refine_near_contacts(contact_points_along(geo,
                                                settings.scene.n_discs,
                                                psi,
                                                request.sweep,
                                                load_sign),
                           settings.mesh.contact_refinement_radius,
                           settings.mesh.contact_refinements,
                           tria);
    }



    template <int dim>
    std::unique_ptr<dealii::parallel::TriangulationBase<dim>>
    create_triangulation(const MeshParameters &settings, const MPI_Comm comm)
    {
      const auto smoothing =
        dealii::Triangulation<dim>::limit_level_difference_at_vertices;
      if (settings.distributed)
        return std::make_unique<
          dealii::parallel::distributed::Triangulation<dim>>(comm, smoothing);
      return std::make_unique<dealii::parallel::shared::Triangulation<dim>>(
        comm,
        smoothing,
        false,
        dealii::parallel::shared::Triangulation<dim>::partition_metis);
    }



    template std::unique_ptr<dealii::parallel::TriangulationBase<2>>
    create_triangulation<2>(const MeshParameters &, const MPI_Comm);
    template std::unique_ptr<dealii::parallel::TriangulationBase<3>>
    create_triangulation<3>(const MeshParameters &, const MPI_Comm);

    template void
    create_stage_mesh<2>(const MeshSettings &,
                         const MeshRequest &,
                         dealii::Triangulation<2> &);
    template void
    create_stage_mesh<3>(const MeshSettings &,
                         const MeshRequest &,
                         dealii::Triangulation<3> &);
  } // namespace mesh
} // namespace cycloid

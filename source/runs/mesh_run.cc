#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>

#include <cycloid/mesh/stage_mesh.h>
#include <cycloid/postprocess/mesh_output.h>
#include <cycloid/results/stage_state.h>
#include <cycloid/runs/mesh_run.h>
#include <cycloid/stage/cost_estimate.h>

#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace cycloid
{
  namespace runs
  {
    template <int dim>
    MeshRun<dim>::MeshRun(const Settings &settings, const MPI_Comm comm)
      : settings(settings)
      , comm(comm)
    {}



    namespace
    {
      /** The cost estimate of an FE run on @p tria (its DoFs with the
       * scene's elements), and whether it would fit into the memory. */
      template <int dim>
      std::string
      cost_line(const mesh::MeshSettings                           &settings,
                const dealii::parallel::shared::Triangulation<dim> &tria,
                const MPI_Comm                                      comm)
      {
        const dealii::FESystem<dim> fe(dealii::FE_Q<dim>(settings.mesh.degree),
                                       dim);
        dealii::DoFHandler<dim>     dofs(tria);
        dofs.distribute_dofs(fe);
        stage::CostInputs in{dim,
                             settings.scene.n_discs,
                             dofs.n_dofs(),
                             settings.mesh.degree,
                             settings.mesh.adaptive_cycles,
                             dealii::Utilities::MPI::n_mpi_processes(comm)};
        // The estimate and its bulk level as the FE run would resolve
        // them (AllParameters resolves both for Run = mesh too).
        in.error_estimate      = settings.mesh.error.estimates(dim);
        in.bulk_estimate       = settings.mesh.error.bulk_level(dim);
        const auto   estimate  = stage::estimate_cost(in);
        const double available = stage::available_memory_bytes(comm);
        // A mesh run allocates no matrix: it warns where an FE run stops.
        return "  FE run on this mesh: " + estimate.line() +
               (estimate.memory_bytes > available ?
                  "\nwarning: an FE run on this mesh would not fit into the "
                  "available memory (" +
                    std::to_string(static_cast<long>(available / 1e6)) +
                    " MB); it would stop before the solve" :
                  "");
      }

      /** @brief The worst cell of a mesh by scaled Jacobian. */
      struct WorstCell
      {
        double           jacobian = 1;
        std::string      body;
        dealii::Point<3> centre;
      };

      /** mesh.csv's text (one row a body) into @p table; the worst cell. */
      WorstCell
      quality_table(const std::vector<mesh::BodyStatistics> &stats,
                    std::ostream                            &table)
      {
        table << "body,material_id,cells,vertices,measure,min_scaled_jacobian,"
                 "max_aspect_ratio\n";
        WorstCell worst;
        for (const auto &s : stats)
          {
            table << mesh::ids::body_name(s.material_id) << ',' << s.material_id
                  << ',' << s.n_cells << ',' << s.n_vertices << ','
                  << std::setprecision(12) << s.measure << ','
                  << s.min_scaled_jacobian << ',' << s.max_aspect_ratio << '\n';
            if (s.min_scaled_jacobian < worst.jacobian)
              worst = {s.min_scaled_jacobian,
                       mesh::ids::body_name(s.material_id),
                       s.worst_cell};
          }
        return worst;
      }

      /** @brief The console's summary of the bodies. */
      struct BodySummary
      {
        unsigned int disc_cells = 0, pin_cells = 0, housing_cells = 0;
        double       max_aspect = 1;
        /** One line a disc and the housing, one for all pins. */
        std::string per_body;
      };

      /** The cells of each kind of body, the largest aspect ratio and a
       * line a body (the pins' range in one). */
      BodySummary
      summarise_bodies(const std::vector<mesh::BodyStatistics> &stats)
      {
        BodySummary        summary;
        unsigned int       pin_min = ~0u, pin_max = 0;
        std::ostringstream per_body;
        for (const auto &s : stats)
          if (mesh::ids::is_pin(s.material_id))
            {
              pin_min = std::min(pin_min, s.n_cells);
              pin_max = std::max(pin_max, s.n_cells);
            }
          else
            per_body << "\n    " << mesh::ids::body_name(s.material_id) << ": "
                     << s.n_cells << " cells, " << s.n_vertices
                     << " vertices, min scaled Jacobian "
                     << s.min_scaled_jacobian;
        per_body << "\n    each pin: " << pin_min << " to " << pin_max
                 << " cells";
        for (const auto &s : stats)
          {
            (mesh::ids::is_disc(s.material_id) ? summary.disc_cells :
             mesh::ids::is_pin(s.material_id)  ? summary.pin_cells :
                                                 summary.housing_cells) +=
              s.n_cells;
            summary.max_aspect =
              std::max(summary.max_aspect, s.max_aspect_ratio);
          }
        summary.per_body = per_body.str();
        return summary;
      }
    } // namespace



    template <int dim>
    void
    MeshRun<dim>::run()
    {
      const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      const std::string &dir   = settings.output_directory;
      const auto        &scene = settings.mesh.scene;
      const auto         start = std::chrono::steady_clock::now();
      // Every rank holds the whole (coarse and refined) mesh, partitioned
      // with METIS; see doc/mesh.md for why not p4est or a fully
      // distributed triangulation.
      dealii::parallel::shared::Triangulation<dim> tria(
        comm,
        dealii::Triangulation<dim>::limit_level_difference_at_vertices,
        false,
        dealii::parallel::shared::Triangulation<dim>::partition_metis);
      mesh::create_stage_mesh(settings.mesh, settings.request, tria);
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();

      const std::string cost  = cost_line(settings.mesh, tria, comm);
      const auto        stats = mesh::body_statistics(tria);
      postprocess::write_mesh_vtu(tria, dir, "mesh", comm);

      std::ostringstream table;
      const WorstCell    worst = quality_table(stats, table);
      if (root)
        {
          std::ofstream(dir + "/mesh.csv") << table.str();
          const BodySummary b = summarise_bodies(stats);
          std::cout << "cycloid-contact: " << dim << "D mesh of "
                    << scene.n_discs << " disc(s), "
                    << settings.mesh.geometry.n_pins << " pins"
                    << (b.housing_cells > 0 ? ", housing" : "")
                    << " at crank angle "
                    << settings.request.crank_angle *
                         results::units::deg_per_rad
                    << " deg on "
                    << dealii::Utilities::MPI::n_mpi_processes(comm)
                    << " rank(s) (METIS partition)\n"
                    << "  cells: " << tria.n_active_cells() << " (discs "
                    << b.disc_cells << ", pins " << b.pin_cells << ", housing "
                    << b.housing_cells << "), vertices " << tria.n_vertices()
                    << b.per_body << "\n  quality: min scaled Jacobian "
                    << worst.jacobian << " (" << worst.body << ", cell at "
                    << worst.centre << "), max aspect ratio " << b.max_aspect
                    << "\n  generated in " << seconds << " s; written " << dir
                    << "/mesh.pvtu, "
                    << "mesh_boundary.pvtu, mesh.csv\n"
                    << cost << std::endl;
        }
      AssertThrow(
        worst.jacobian > 1e-3,
        dealii::ExcMessage(
          "mesh: inverted or degenerate cells in " + worst.body +
          " (worst at " + dealii::Utilities::to_string(worst.centre[0]) + ", " +
          dealii::Utilities::to_string(worst.centre[1]) + ", " +
          dealii::Utilities::to_string(worst.centre[2]) + " mm)" +
          " (minimum scaled Jacobian " + std::to_string(worst.jacobian) +
          "). Reduce the Mesh element sizes or the Size grading; "
          "the mesh was written to " +
          dir +
          "/mesh.pvtu for "
          "inspection."));
    }

    template class MeshRun<2>;
    template class MeshRun<3>;
  } // namespace runs
} // namespace cycloid

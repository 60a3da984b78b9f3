#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>

#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <cycloid/postprocess/mesh_output.h>

#include <fstream>
#include <map>
#include <vector>

namespace cycloid
{
  namespace postprocess
  {
    namespace
    {
      /** One VTU piece: points, cells of one VTK type, integer cell data. */
      struct Piece
      {
        std::vector<double>                                   points;
        std::vector<unsigned int>                             connectivity;
        unsigned int                                          nodes_per_cell;
        unsigned int                                          vtk_type;
        std::vector<std::pair<std::string, std::vector<int>>> data;
        std::map<unsigned int, unsigned int>                  index;

        template <int dim>
        unsigned int
        point(const unsigned int global, const dealii::Point<dim> &p)
        {
          auto it = index.find(global);
          if (it != index.end())
            return it->second;
          const unsigned int i = index.size();
          index[global]        = i;
          for (unsigned int c = 0; c < 3; ++c)
            points.push_back(c < dim ? p[c] : 0.);
          return i;
        }

        void
        write(const std::string &file) const
        {
          std::ofstream out(file);
          AssertThrow(out, dealii::ExcMessage("cannot write " + file));
          const std::size_t n_cells = connectivity.size() / nodes_per_cell;
          out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" "
                 "version=\"0.1\" byte_order=\"LittleEndian\">\n"
                 "<UnstructuredGrid>\n<Piece NumberOfPoints=\""
              << points.size() / 3 << "\" NumberOfCells=\"" << n_cells
              << "\">\n<Points>\n<DataArray type=\"Float64\" "
                 "NumberOfComponents=\"3\" format=\"ascii\">\n";
          out.precision(16);
          for (std::size_t i = 0; i < points.size(); ++i)
            out << points[i] << ((i % 3 == 2) ? '\n' : ' ');
          out << "</DataArray>\n</Points>\n<Cells>\n<DataArray "
                 "type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
          for (std::size_t i = 0; i < connectivity.size(); ++i)
            out << connectivity[i]
                << ((i % nodes_per_cell == nodes_per_cell - 1) ? '\n' : ' ');
          out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" "
                 "format=\"ascii\">\n";
          for (std::size_t c = 1; c <= n_cells; ++c)
            out << c * nodes_per_cell << '\n';
          out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" "
                 "format=\"ascii\">\n";
          for (std::size_t c = 0; c < n_cells; ++c)
            out << vtk_type << '\n';
          out << "</DataArray>\n</Cells>\n<CellData>\n";
          for (const auto &[name, values] : data)
            {
              out << "<DataArray type=\"Int32\" Name=\"" << name
                  << "\" format=\"ascii\">\n";
              for (const int v : values)
                out << v << '\n';
              out << "</DataArray>\n";
            }
          out << "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
        }
      };

      void
      write_pvtu(const std::string              &file,
                 const std::string              &piece_prefix,
                 const std::vector<std::string> &names,
                 const unsigned int              n_ranks)
      {
        std::ofstream out(file);
        AssertThrow(out, dealii::ExcMessage("cannot write " + file));
        out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" "
               "version=\"0.1\" byte_order=\"LittleEndian\">\n"
               "<PUnstructuredGrid GhostLevel=\"0\">\n<PPoints>\n"
               "<PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
               "</PPoints>\n<PCellData>\n";
        for (const auto &n : names)
          out << "<PDataArray type=\"Int32\" Name=\"" << n << "\"/>\n";
        out << "</PCellData>\n";
        for (unsigned int r = 0; r < n_ranks; ++r)
          out << "<Piece Source=\"" << piece_prefix << "-" << r << ".vtu\"/>\n";
        out << "</PUnstructuredGrid>\n</VTKFile>\n";
      }
    } // namespace



    template <int dim>
    void
    write_mesh_vtu(const dealii::Triangulation<dim> &tria,
                   const std::string                &directory,
                   const std::string                &name,
                   const MPI_Comm                    comm)
    {
      const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(comm);
      const unsigned int n_ranks =
        dealii::Utilities::MPI::n_mpi_processes(comm);
      // deal.II lexicographic -> VTK vertex order.
      const unsigned int to_vtk[8] = {0, 1, 3, 2, 4, 5, 7, 6};

      Piece cells, faces;
      cells.nodes_per_cell = dealii::GeometryInfo<dim>::vertices_per_cell;
      cells.vtk_type       = (dim == 2) ? 9 : 12; // VTK_QUAD, VTK_HEXAHEDRON
      faces.nodes_per_cell = dealii::GeometryInfo<dim - 1>::vertices_per_cell;
      faces.vtk_type       = (dim == 2) ? 3 : 9; // VTK_LINE, VTK_QUAD
      std::vector<int> body, owner, level, f_boundary, f_body, f_owner;
      for (const auto &cell : tria.active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          for (unsigned int v = 0; v < cells.nodes_per_cell; ++v)
            cells.connectivity.push_back(
              cells.point(cell->vertex_index(to_vtk[v]),
                          cell->vertex(to_vtk[v])));
          body.push_back(cell->material_id());
          owner.push_back(cell->subdomain_id());
          level.push_back(cell->level());
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              {
                const auto face = cell->face(f);
                for (unsigned int v = 0; v < faces.nodes_per_cell; ++v)
                  faces.connectivity.push_back(
                    faces.point(face->vertex_index(to_vtk[v]),
                                face->vertex(to_vtk[v])));
                f_boundary.push_back(face->boundary_id());
                f_body.push_back(cell->material_id());
                f_owner.push_back(cell->subdomain_id());
              }
        }
      cells.data = {{"body_id", body}, {"mpi_rank", owner}, {"level", level}};
      faces.data = {{"boundary_id", f_boundary},
                    {"body_id", f_body},
                    {"mpi_rank", f_owner}};
      const std::string base = directory + "/" + name;
      cells.write(base + "-" + std::to_string(rank) + ".vtu");
      faces.write(base + "_boundary-" + std::to_string(rank) + ".vtu");
      if (rank == 0)
        {
          write_pvtu(base + ".pvtu",
                     name,
                     {"body_id", "mpi_rank", "level"},
                     n_ranks);
          write_pvtu(base + "_boundary.pvtu",
                     name + "_boundary",
                     {"boundary_id", "body_id", "mpi_rank"},
                     n_ranks);
        }
      dealii::Utilities::MPI::sum(0, comm); // all pieces exist on return
    }

    template void
    write_mesh_vtu<2>(const dealii::Triangulation<2> &,
                      const std::string &,
                      const std::string &,
                      const MPI_Comm);
    template void
    write_mesh_vtu<3>(const dealii::Triangulation<3> &,
                      const std::string &,
                      const std::string &,
                      const MPI_Comm);
  } // namespace postprocess
} // namespace cycloid

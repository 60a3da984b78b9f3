#include <deal.II/grid/grid_tools.h>

#include <cycloid/mesh/extrusion.h>
#include <cycloid/mesh/ids.h>

#include <map>

namespace cycloid
{
  namespace mesh
  {
    namespace
    {
      /** gmsh -> deal.II vertex order (lexicographic); a hexahedron is a
       * gmsh quadrilateral at two z levels. */
      constexpr unsigned int to_dealii[8] = {0, 1, 3, 2, 4, 5, 7, 6};



      /** The section's quadrilaterals as deal.II cells (plane strain). */
      void
      section_cells(const internal::RawMesh          &raw,
                    std::vector<dealii::Point<2>>    &vertices,
                    std::vector<dealii::CellData<2>> &cells)
      {
        vertices.resize(raw.coordinates.size() / 3);
        for (std::size_t v = 0; v < vertices.size(); ++v)
          for (unsigned int c = 0; c < 2; ++c)
            vertices[v][c] = raw.coordinates[3 * v + c];
        cells.resize(raw.materials.size());
        for (std::size_t c = 0; c < cells.size(); ++c)
          {
            for (unsigned int v = 0; v < 4; ++v)
              cells[c].vertices[v] = raw.cells[4 * c + to_dealii[v]];
            cells[c].material_id = raw.materials[c];
          }
      }



      /** The z levels of body @p m: a disc through its width, pins and
       * housing through both discs and the gap, with matching layers so
       * that the bodies' faces conform where they touch. */
      std::vector<double>
      axial_levels(const MeshSettings              &settings,
                   const dealii::types::material_id m)
      {
        std::vector<double> z;
        const auto          add = [&](const double       z0,
                             const double       z1,
                             const unsigned int n,
                             const bool         first) {
          for (unsigned int k = first ? 0 : 1; k <= n; ++k)
            z.push_back(z0 + (z1 - z0) * k / n);
        };
        const unsigned int nl = settings.mesh.axial_layers;
        if (ids::is_disc(m))
          {
            const auto r = disc_axial_range(settings, m);
            add(r.first, r.second, nl, true);
          }
        else
          {
            const auto r0 = disc_axial_range(settings, 0);
            add(r0.first, r0.second, nl, true);
            if (settings.scene.n_discs == 2)
              {
                const auto r1 = disc_axial_range(settings, 1);
                add(r0.second, r1.first, settings.mesh.gap_layers, false);
                add(r1.first, r1.second, nl, false);
              }
          }
        return z;
      }



      /** The section's quadrilaterals extruded into hexahedra through each
       * body's axial_levels(). */
      void
      extruded_cells(const MeshSettings               &settings,
                     const internal::RawMesh          &raw,
                     std::vector<dealii::Point<3>>    &vertices,
                     std::vector<dealii::CellData<3>> &cells)
      {
        std::map<dealii::types::material_id, std::vector<double>>     z_of;
        std::map<std::pair<unsigned int, unsigned int>, unsigned int> index;
        // Vertex v2 of the section at level k; the first z given for it
        // wins (the bodies do not share section vertices).
        const auto vertex = [&](const unsigned int         v2,
                                const unsigned int         k,
                                const std::vector<double> &z) {
          const auto key = std::make_pair(v2, k);
          auto       it  = index.find(key);
          if (it != index.end())
            return it->second;
          dealii::Point<3> p;
          p[0] = raw.coordinates[3 * v2];
          p[1] = raw.coordinates[3 * v2 + 1];
          p[2] = z[k];
          vertices.push_back(p);
          return index[key] = vertices.size() - 1;
        };
        for (std::size_t q = 0; q < raw.materials.size(); ++q)
          {
            const auto m = raw.materials[q];
            if (z_of.find(m) == z_of.end())
              z_of[m] = axial_levels(settings, m);
            const std::vector<double> &z = z_of[m];
            for (unsigned int k = 0; k + 1 < z.size(); ++k)
              {
                dealii::CellData<3> cell;
                unsigned int        hex[8];
                for (unsigned int v = 0; v < 4; ++v)
                  {
                    hex[v]     = vertex(raw.cells[4 * q + v], k, z);
                    hex[v + 4] = vertex(raw.cells[4 * q + v], k + 1, z);
                  }
                for (unsigned int v = 0; v < 8; ++v)
                  cell.vertices[v] = hex[to_dealii[v]];
                cell.material_id = m;
                cells.push_back(cell);
              }
          }
      }
    } // namespace



    std::pair<double, double>
    disc_axial_range(const MeshSettings &settings, const unsigned int d)
    {
      const auto  &g  = settings.geometry;
      const double z0 = d * (g.tooth_width + g.axial_gap);
      return {z0, z0 + g.tooth_width};
    }



    template <int dim>
    void
    internal::create_from_section(const MeshSettings         &settings,
                                  const RawMesh              &raw,
                                  dealii::Triangulation<dim> &tria)
    {
      std::vector<dealii::Point<dim>>    vertices;
      std::vector<dealii::CellData<dim>> cells;
      if constexpr (dim == 2)
        section_cells(raw, vertices, cells);
      else
        extruded_cells(settings, raw, vertices, cells);
      // gmsh orients each surface on its own: flip the cells that came out
      // clockwise (negative measure in deal.II's orientation).
      dealii::GridTools::invert_cells_with_negative_measure(vertices, cells);
      dealii::GridTools::consistently_order_cells(cells);
      tria.create_triangulation(vertices, cells, dealii::SubCellData());
    }



    template void
    internal::create_from_section<2>(const MeshSettings &,
                                     const internal::RawMesh &,
                                     dealii::Triangulation<2> &);
    template void
    internal::create_from_section<3>(const MeshSettings &,
                                     const internal::RawMesh &,
                                     dealii::Triangulation<3> &);
  } // namespace mesh
} // namespace cycloid

#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <cycloid/mesh/mesh_statistics.h>

#include <algorithm>
#include <limits>
#include <map>
#include <set>

namespace cycloid
{
  namespace mesh
  {
    template <int dim>
    std::vector<BodyStatistics>
    body_statistics(const dealii::Triangulation<dim> &tria)
    {
      std::map<dealii::types::material_id, BodyStatistics>         stats;
      std::map<dealii::types::material_id, std::set<unsigned int>> verts;
      for (const auto &cell : tria.active_cell_iterators())
        {
          BodyStatistics &s = stats[cell->material_id()];
          s.material_id     = cell->material_id();
          ++s.n_cells;
          s.measure += cell->measure();
          for (const unsigned int v : cell->vertex_indices())
            {
              verts[cell->material_id()].insert(cell->vertex_index(v));
              // Scaled Jacobian at vertex v: the dim edges from it, in the
              // cell's right-handed order.
              dealii::Tensor<1, dim> e[dim];
              double                 sign = 1;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  e[d] = cell->vertex(v ^ (1u << d)) - cell->vertex(v);
                  if (v & (1u << d))
                    sign = -sign;
                }
              double det = 0, norms = 1;
              if (dim == 2)
                det = e[0][0] * e[1][1] - e[0][1] * e[1][0];
              else
                {
                  dealii::Tensor<1, 3> a, b, c;
                  for (unsigned int k = 0; k < 3; ++k)
                    {
                      a[k] = e[0][k];
                      b[k] = e[1][k];
                      c[k] = e[dim - 1][k];
                    }
                  det = dealii::cross_product_3d(a, b) * c;
                }
              for (unsigned int d = 0; d < dim; ++d)
                norms *= e[d].norm();
              if (sign * det / norms < s.min_scaled_jacobian)
                {
                  s.min_scaled_jacobian = sign * det / norms;
                  for (unsigned int d = 0; d < dim; ++d)
                    s.worst_cell[d] = cell->center()[d];
                }
            }
          double longest = 0, shortest = std::numeric_limits<double>::max();
          for (const unsigned int l : cell->line_indices())
            {
              const double length = cell->line(l)->diameter();
              longest             = std::max(longest, length);
              shortest            = std::min(shortest, length);
            }
          s.max_aspect_ratio = std::max(s.max_aspect_ratio, longest / shortest);
        }
      std::vector<BodyStatistics> result;
      for (auto &[m, s] : stats)
        {
          s.n_vertices = verts[m].size();
          result.push_back(s);
        }
      return result;
    }



    template std::vector<BodyStatistics>
    body_statistics<2>(const dealii::Triangulation<2> &);
    template std::vector<BodyStatistics>
    body_statistics<3>(const dealii::Triangulation<3> &);
  } // namespace mesh
} // namespace cycloid

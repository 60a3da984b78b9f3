#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <cycloid/mesh/contact_refinement.h>

#include <algorithm>
#include <cmath>

namespace cycloid
{
  namespace mesh
  {
    std::vector<dealii::Point<2>>
    contact_points(const geometry::CycloidGeometry &geometry,
                   const unsigned int               n_discs,
                   const double                     psi)
    {
      std::vector<dealii::Point<2>> points;
      for (unsigned int d = 0; d < n_discs; ++d)
        for (const auto &c : geometry.pin_contacts(d, psi))
          points.push_back(c.contact_point);
      return points;
    }



    std::vector<dealii::Point<2>>
    contact_points_along(const geometry::CycloidGeometry &geometry,
                         const unsigned int               n_discs,
                         const double                     psi,
                         const double                     sweep,
                         const int                        load_sign)
    {
      if (sweep == 0. && load_sign == 0)
        return contact_points(geometry, n_discs, psi);
      const unsigned int n =
        sweep == 0. ? 1 :
                      static_cast<unsigned int>(std::ceil(
                        std::abs(sweep) / (geometry.mesh_period() / 20.)));
      std::vector<dealii::Point<2>> points;
      for (unsigned int k = 0; k <= (sweep == 0. ? 0 : n); ++k)
        {
          const double s = psi + sweep * k / n;
          for (unsigned int d = 0; d < n_discs; ++d)
            {
              const auto contacts = geometry.pin_contacts(d, s);
              double     largest  = 0;
              for (const auto &c : contacts)
                largest = std::max(largest, std::abs(c.arm));
              for (const auto &c : contacts)
                {
                  if (load_sign != 0 && c.arm * load_sign < -0.05 * largest)
                    continue;
                  points.push_back(c.contact_point);
                  if (sweep != 0.)
                    points.push_back(geometry.to_housing(
                      d, psi, geometry.to_disc(d, s, c.contact_point)));
                }
            }
        }
      return points;
    }



    namespace
    {
      /** The radius of the cell's bounding circle about its centre in the
       * section plane (x, y). */
      template <int dim>
      double
      section_radius(
        const typename dealii::Triangulation<dim>::active_cell_iterator &cell)
      {
        const auto c = cell->center();
        double     r = 0;
        for (const unsigned int v : cell->vertex_indices())
          r = std::max(r,
                       std::hypot(cell->vertex(v)[0] - c[0],
                                  cell->vertex(v)[1] - c[1]));
        return r;
      }
    } // namespace



    template <int dim>
    void
    refine_near_contacts(const std::vector<dealii::Point<2>> &points,
                         const double                         radius,
                         const unsigned int                   n_cycles,
                         dealii::Triangulation<dim>          &tria)
    {
      for (unsigned int cycle = 0; cycle < n_cycles; ++cycle)
        {
          for (const auto &cell : tria.active_cell_iterators())
            {
              if (cell->is_artificial())
                continue;
              // A cell is near a contact point if the point lies within
              // radius of the cell's bounding circle.
              const auto   c = cell->center();
              const double r = section_radius<dim>(cell);
              for (const auto &p : points)
                if (std::hypot(p[0] - c[0], p[1] - c[1]) < radius + r)
                  {
                    cell->set_refine_flag();
                    break;
                  }
            }
          tria.execute_coarsening_and_refinement();
        }
    }



    template <int dim>
    bool
    near_contact_node(
      const typename dealii::Triangulation<dim>::active_cell_iterator &cell,
      const dealii::Point<dim>                                        &p)
    {
      const auto c = cell->center();
      if (dim == 2)
        return p.distance(c) < 2 * cell->diameter();
      // In-plane size and axial span of the cell.
      const double size  = 2 * section_radius<dim>(cell);
      double       z_low = c[dim - 1], z_high = z_low;
      for (const unsigned int v : cell->vertex_indices())
        {
          z_low  = std::min(z_low, cell->vertex(v)[dim - 1]);
          z_high = std::max(z_high, cell->vertex(v)[dim - 1]);
        }
      const double axial_distance =
        std::max({0., z_low - p[dim - 1], p[dim - 1] - z_high});
      return std::hypot(p[0] - c[0], p[1] - c[1]) < 2 * size &&
             axial_distance < 2 * size;
    }



    template void
    refine_near_contacts<2>(const std::vector<dealii::Point<2>> &,
                            const double,
                            const unsigned int,
                            dealii::Triangulation<2> &);
    template void
    refine_near_contacts<3>(const std::vector<dealii::Point<2>> &,
                            const double,
                            const unsigned int,
                            dealii::Triangulation<3> &);
    template bool
    near_contact_node<2>(const dealii::Triangulation<2>::active_cell_iterator &,
                         const dealii::Point<2> &);
    template bool
    near_contact_node<3>(const dealii::Triangulation<3>::active_cell_iterator &,
                         const dealii::Point<3> &);
  } // namespace mesh
} // namespace cycloid

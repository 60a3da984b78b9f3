#ifndef cycloid_elasticity_support_points_h
#define cycloid_elasticity_support_points_h

#include <deal.II/base/quadrature.h>

#include <deal.II/fe/fe_values.h>

#include <cycloid/elasticity/elasticity.h>

namespace cycloid
{
  namespace elasticity
  {
    /**
     * @brief FEValues at the support points of the cells of @p el: after
     * reinit(cell), quadrature point k is the position of the cell's node k
     * on the exact mapping. For loops that set a value per node (supports,
     * load fields, rigid-body fields).
     */
    template <int dim>
    dealii::FEValues<dim>
    support_point_values(const LinearElasticity<dim> &el)
    {
      const auto                   &fe = el.finite_element();
      const dealii::Quadrature<dim> nodes(
        fe.base_element(0).get_unit_support_points());
      return dealii::FEValues<dim>(el.mapping(),
                                   fe,
                                   nodes,
                                   dealii::update_quadrature_points);
    }
  } // namespace elasticity
} // namespace cycloid

#endif

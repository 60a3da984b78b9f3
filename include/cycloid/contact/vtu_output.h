#ifndef cycloid_contact_vtu_output_h
#define cycloid_contact_vtu_output_h

#include <deal.II/base/types.h>

#include <cycloid/contact/contact_types.h>
#include <cycloid/elasticity/elasticity.h>
#include <cycloid/parameters/material.h>

#include <map>
#include <string>
#include <vector>

namespace cycloid
{
  namespace contact
  {
    /**
     * Write a contact state as @p directory/@p name.pvtu (+ one .vtu per
     * rank): the displacement, the von Mises stress (2D: plane strain) of
     * each body's material in @p materials, per slave node the contact
     * pressure [MPa] (normal reaction / node weight), the active flag and
     * (3D) the gap [um], and per cell the body id and MPI rank. Collective.
     */
    template <int dim>
    void
    write_vtu(const elasticity::LinearElasticity<dim>     &problem,
              const std::map<dealii::types::material_id,
                             parameters::ElasticMaterial> &materials,
              const std::vector<SlaveNode<dim>>           &slaves,
              const ContactSolution<dim>                  &solution,
              const std::string                           &directory,
              const std::string                           &name);
  } // namespace contact
} // namespace cycloid

#endif

#ifndef cycloid_contact_node_to_surface_h
#define cycloid_contact_node_to_surface_h

#include <cycloid/contact/constraint_formulation.h>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief Node-to-surface constraint: collocation at the slave node,
     * n_i . (u_i - u_M(P_i)) = -g(x_i), with the unit normal n_i at the
     * node and P_i its projection onto the cylinder. Cheap, but fails the
     * contact patch test on non-matching meshes (see Formulation).
     */
    template <int dim>
    class NodeToSurface : public ConstraintFormulation<dim>
    {
    public:
      /** "node-to-surface". */
      std::string
      name() const override;

      /** Keep the collocated normal; for a deformable master, the master
       * coefficients n_c N_m(P_i) of the master shape functions at P_i. */
      void
      couple(const SurfaceSearch<dim>    &search,
             std::vector<SlaveNode<dim>> &slaves) const override;
    };
  } // namespace contact
} // namespace cycloid

#endif

#ifndef cycloid_contact_mortar_h
#define cycloid_contact_mortar_h

#include <cycloid/contact/constraint_formulation.h>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief Dual mortar constraint (Wohlmuth): the normal and the master
     * displacement weighted with the dual (biorthogonal) basis psi_i of the
     * slave faces, n_i = int psi_i n ds / w_i and c_im = int psi_i n . phi_m
     * ds / w_i (w_i = int phi_i ds), by quadrature on the slave faces. The
     * initial gap stays collocated at the node (see Formulation for why).
     */
    template <int dim>
    class Mortar : public ConstraintFormulation<dim>
    {
    public:
      /** "mortar". */
      std::string
      name() const override;

      /** Replace each slave node's normal and master coefficients by their
       * dual-basis weighted averages over the slave faces. */
      void
      couple(const SurfaceSearch<dim>    &search,
             std::vector<SlaveNode<dim>> &slaves) const override;
    };
  } // namespace contact
} // namespace cycloid

#endif

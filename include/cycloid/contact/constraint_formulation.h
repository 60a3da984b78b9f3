#ifndef cycloid_contact_constraint_formulation_h
#define cycloid_contact_constraint_formulation_h

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/contact/contact_types.h>
#include <cycloid/contact/surface_search.h>

#include <memory>
#include <string>
#include <vector>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief Discretisation of the contact constraint of the slave nodes
     * (see Formulation for the two implementations, NodeToSurface and
     * Mortar).
     *
     * Every implementation reduces the constraint of a slave node i to the
     * one-node form
     * @f[ n_i \cdot u_i - \sum_m c_{im} u_m = -g_i @f]
     * (slave part diagonal, u_m the master DoFs), so they differ only in
     * the normal n_i and the master coefficients c_im that couple()
     * computes; the constraint line of an active node (constrain()) and the
     * discrete gap (gap()) are common to all of them.
     */
    template <int dim>
    class ConstraintFormulation
    {
    public:
      /** Virtual: implementations are held through this interface. */
      virtual ~ConstraintFormulation() = default;

      /** The name, as in Contact/Formulation and create_formulation(). */
      virtual std::string
      name() const = 0;

      /**
       * Set the normal and the master coefficients of the @p slaves, which
       * come from SurfaceSearch::find_slave_nodes() with the collocated
       * unit normal and no master coefficients; @p search gives the
       * geometry (cylinders, placement, master weights).
       */
      virtual void
      couple(const SurfaceSearch<dim>    &search,
             std::vector<SlaveNode<dim>> &slaves) const = 0;

      /**
       * Add the constraint of the active node @p s to @p c, eliminating its
       * dominant normal component (step-41/42: the matrix stays SPD). With
       * @p with_gaps the inhomogeneity holds the initial gap, else zero
       * (the load-direction set of the superposition). Nothing if the line
       * is stored elsewhere or already constrained.
       */
      void
      constrain(dealii::AffineConstraints<double> &c,
                const SlaveNode<dim>              &s,
                const bool                         with_gaps) const;

      /** Gap of node @p s [mm] for the displacement u0 + beta u1 (ghosted
       * vectors holding the node's and its masters' DoFs). */
      double
      gap(const SlaveNode<dim>                        &s,
          const dealii::TrilinosWrappers::MPI::Vector &u0,
          const dealii::TrilinosWrappers::MPI::Vector &u1,
          const double                                 beta) const;
    };

    /** The name of @p formulation as create_formulation() takes it
     * ("mortar", "node-to-surface"). */
    std::string
    formulation_name(const Formulation formulation);

    /** The formulation called @p name ("mortar" or "node-to-surface");
     * throws for another name. */
    template <int dim>
    std::unique_ptr<ConstraintFormulation<dim>>
    create_formulation(const std::string &name);
  } // namespace contact
} // namespace cycloid

#endif

#ifndef cycloid_reduced_compliance_h
#define cycloid_reduced_compliance_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/full_matrix.h>

#include <cycloid/contact/contact_problem.h>
#include <cycloid/elasticity/elasticity.h>

#include <ostream>
#include <vector>

namespace cycloid
{
  namespace reduced
  {
    /**
     * @brief One contact of the reduced model: a pin against a disc (in 3D
     * against an axial slice of the disc), where the coarse FE model is
     * loaded and its compliance measured.
     */
    struct ContactPoint
    {
      /** Disc index. */
      unsigned int disc = 0;
      /** Pin index. */
      unsigned int pin = 0;
      /** Closest point of the disc profile to the pin centre, in the
       * housing frame [mm]. */
      dealii::Point<2> point;
      /** Unit contact normal from the disc towards the pin (housing
       * frame). */
      dealii::Tensor<1, 2> normal;
      /** The same material point of the disc where the coarse model's disc
       * lies (its mesh may be at another crank angle: the disc is a rigid
       * motion away, and its compliance does not change with that) [mm]. */
      dealii::Point<2> disc_point;
      /** The normal at disc_point, turned with the disc. */
      dealii::Tensor<1, 2> disc_normal;
      /** Initial clearance along the normal [mm]. */
      double clearance = 0;
      /** 3D: the axial slice [z_min, z_max] the force acts on [mm]. */
      double z_min = 0;
      /** 3D: upper end of the slice [mm]. */
      double z_max = 0;
    };

    /**
     * @brief What the condensation produced: the compliance matrix and its
     * cost.
     */
    struct Compliance
    {
      /**
       * C(i, k): increase of the separation of contact i (pin minus disc
       * displacement along the normal, pressure-weighted over the load of
       * i) per unit force of the load of contact k [mm/N; 2D: per N/mm of
       * thickness]. Symmetric (Maxwell-Betti; made exact by averaging).
       */
      dealii::FullMatrix<double> matrix;
      /** Largest |C(i,k) - C(k,i)| / max C(i,i) before the averaging: a
       * check of the solves [-]. */
      double asymmetry = 0;
      /** Linear-solver iterations over all load cases. */
      unsigned long linear_iterations = 0;
    };

    /**
     * @brief Condense the compliance of every body of @p contact onto the
     * contacts @p points, on the operator of
     * ContactProblem::assemble_without_contact() (assembled by the caller:
     * the bodies held as in every state, crank holes or bore at rest, pin
     * cores or housing held, seats tied, and no contact constraint); one
     * preconditioner (or factorisation) for all load cases, kept for the
     * next call.
     *
     * Load case k is a semi-elliptic pressure of half-width @p w [mm] and
     * unit total force, pressing disc and pin apart along the normal (on
     * the disc's flank around the contact point, on the pin's surface
     * around the point @p clearance further along the normal; in 3D
     * uniform over the slice). Its nodal vector f_k is integrated with a
     * fine face quadrature and scaled to the exact unit force on each
     * body. Then C(i, k) = f_i . u_k: the work-conjugate (pressure-
     * weighted) separation, which makes C symmetric and independent of
     * where a node happens to lie. A direct @p solver computes C = F^T
     * A^{-1} F with one factorisation of kind @p factorisation
     * (LinearElasticity::inverse_form(), every load case in one block);
     * CG + AMG solves the load cases one by one to @p tolerance. The
     * stages are timed in @p timer
     * ("reduced: load vectors", "reduced: solves").
     * If @p progress is given, a line goes there about every tenth of
     * the load cases (and every 30 s) with the cases done and the time.
     */
    template <int dim>
    Compliance
    condense_compliance(contact::ContactProblem<dim>    &contact,
                        const std::vector<ContactPoint> &points,
                        const double                     w,
                        const elasticity::LinearSolver   solver,
                        const elasticity::Factorisation  factorisation,
                        const double                     tolerance,
                        dealii::TimerOutput             &timer,
                        std::ostream                    *progress = nullptr);
  } // namespace reduced
} // namespace cycloid

#endif

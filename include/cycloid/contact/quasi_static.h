#ifndef cycloid_contact_quasi_static_h
#define cycloid_contact_quasi_static_h

#include <deal.II/base/point.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/elasticity/elasticity.h>
#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/parameters/all_parameters.h>
#include <cycloid/postprocess/result_writer.h>

#include <map>
#include <set>
#include <vector>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief One slave node of the node-to-surface contact: a vertex of a
     * disc's tooth flank, paired with its nearest pin.
     */
    struct SlaveNode
    {
      /** Disc and pin. */
      unsigned int disc, pin;
      /** DoF indices of its dim displacement components. */
      std::vector<dealii::types::global_dof_index> dofs;
      /** Reference position [mm]. */
      dealii::Point<2> position;
      /** Unit normal of the pin surface at the closest point, pointing from
       * the pin into the disc. */
      dealii::Tensor<1, 2> normal;
      /** Initial gap to the pin's exact cylinder [mm]. */
      double gap0;
      /** Elastic pins: the pin-surface DoFs (x and y of the two vertices
       * of the pin edge that holds the projection of the node) and their
       * interpolation weights. Empty for rigid pins. */
      std::vector<dealii::types::global_dof_index> master_dofs[2];
      std::vector<double>                          master_weights;
    };

    /**
     * @brief Quasi-static frictionless contact between one disc (2D, plane
     * strain) and rigid or elastic pins, by a primal-dual active set on the
     * flank vertices (work in progress for issue #4: 2D, Q1).
     *
     * Elastic pins are held at their rigid core (all DoFs within `Pin core
     * radius` of the axis); the constraint of an active node then couples
     * the disc node to the pin surface: n . (u_s - u_pin(P)) = -gap0, with
     * u_pin interpolated on the pin edge that holds the node's projection P
     * onto the exact pin cylinder (node-to-surface; the pin DoFs it refers
     * to are ghosted on every rank).
     *
     * Per active-set iteration, the active slave nodes' normal gap is held
     * at zero by an affine constraint that eliminates the node's dominant
     * displacement component (step-41/42 style), which keeps the matrix SPD
     * for CG+AMG. The load is a rigid rotation beta of the crank holes about
     * the disc centre; for a fixed active set the solution is affine in
     * beta, so two solves (gaps with beta = 0; no gaps with beta = 1) give
     * the beta that carries the target torque. The contact force at a slave
     * node is its internal force (the constraint's reaction), the pressure
     * multiplier lambda = n . f_int; the set is updated with
     * lambda + c (-gap) > 0 and the iteration stops when it no longer
     * changes. A set seen before (other than the last one) is cycling and
     * ends the run with an error.
     */
    class QuasiStatic2D
    {
    public:
      /** Build the mesh of the scene at crank angle @p psi. */
      QuasiStatic2D(const parameters::AllParameters &parameters,
                    const double                     psi,
                    const MPI_Comm                   comm);

      /** Solve for output torque @p torque [N m of the whole disc width];
       * fills the rows for the CSV files. */
      void
      solve(const double                           torque,
            postprocess::StiffnessRow             &row,
            std::vector<postprocess::PinForceRow> &pins);

      /**
       * Write the last solved state as solution-NNNN.pvtu (+ one .vtu per
       * rank) with displacement, von Mises stress, contact force and active
       * flag of the slave nodes, body id and MPI rank, and rewrite
       * solution.pvd; @p step numbers the state.
       */
      void
      output_results(const unsigned int step);

    private:
      void
      find_slave_nodes();
      void
      solve_with_active_set(const bool                             with_gaps,
                            const double                           beta,
                            dealii::TrilinosWrappers::MPI::Vector &u);
      double
      reaction_torque(const dealii::TrilinosWrappers::MPI::Vector &f_int) const;

      const parameters::AllParameters                             prm;
      const MPI_Comm                                              comm;
      const double                                                psi;
      const geometry::CycloidGeometry                             geo;
      dealii::parallel::shared::Triangulation<2>                  tria;
      std::unique_ptr<elasticity::LinearElasticity<2>>            problem;
      std::map<dealii::types::global_dof_index, dealii::Point<2>> points;
      std::vector<SlaveNode>                                      slaves;
      std::set<unsigned int>                                      active;
      std::set<dealii::types::global_dof_index> crank_hole_dofs;
      std::set<dealii::types::global_dof_index> pin_dofs;
      std::set<dealii::types::global_dof_index> core_dofs;
      unsigned int                              last_iterations = 0;
      /** Last solved state: displacement and internal forces (ghosted). */
      dealii::TrilinosWrappers::MPI::Vector u_last, f_last;
      /** (state, file) of the written solutions, for the .pvd record. */
      std::vector<std::pair<double, std::string>> written;
    };
  } // namespace contact
} // namespace cycloid

#endif

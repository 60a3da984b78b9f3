#ifndef cycloid_contact_quasi_static_h
#define cycloid_contact_quasi_static_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/shared_tria.h>

#include <cycloid/contact/contact_problem.h>
#include <cycloid/contact/pin_model.h>
#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/parameters/all_parameters.h>
#include <cycloid/postprocess/result_writer.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief Quasi-static FE contact of the cycloid stage at one crank
     * angle: the scene's discs (1 or 2; 2D plane strain or 3D) against its
     * pins (rigid, or elastic and held at their cores or in a meshed
     * housing), loaded by a rigid rotation beta of each disc's crank holes
     * (or bore) about the disc's centre, one beta for both discs, at a
     * target output torque. Wraps a ContactProblem (node-to-surface
     * primal-dual active set) with the stage's geometry, supports, load
     * and post-processing.
     *
     * Stages, each timed (step-42's layout): make_grid(), setup_system()
     * (DoFs, contact nodes, supports, load), solve_state(),
     * refine_at_contacts() (adaptive cycles), pin_forces() and
     * output_results().
     *
     * Pin supports:
     * - `axis` (default): every DoF within `Pin core radius` of a pin's
     *   axis is held (a rigid core; a line or point constraint would make
     *   the pin's compliance mesh dependent);
     * - `housing`: the housing ring is meshed, its outer surface is held and
     *   each groove (seat) node is glued to its pin's surface in every
     *   component (no slip in the seat; a frictionless seat would leave
     *   each pin free to spin about its axis).
     * Rigid pins hold every pin DoF. Forces and torques are reported for
     * the whole tooth width (2D results are per unit thickness internally).
     */
    template <int dim>
    class QuasiStatic
    {
    public:
      /** Build the mesh of the scene at crank angle @p psi [rad] and the
       * contact problem on it; with @p sweep != 0 [rad] the mesh is refined
       * at the contacts of crank angles psi ... psi + sweep (transient runs).
       */
      QuasiStatic(const parameters::AllParameters &parameters,
                  const double                     psi,
                  const MPI_Comm                   comm,
                  const double                     sweep = 0.);

      virtual ~QuasiStatic() = default;

      /**
       * Solve for output torque @p load [N m] (or, with Loading/Control =
       * rotation, for the rotation @p load [rad]), warm-started from the
       * previous state, or for the first from the analytical model (the
       * rigid rotation), with
       * `Mesh/Adaptive refinement cycles` refinements at the active
       * contact; fill the CSV rows.
       */
      void
      solve(const double                           load,
            postprocess::StiffnessRow             &row,
            std::vector<postprocess::PinForceRow> &pins);

      /** The active set with node positions, to warm-start another crank
       * angle (see warm_start()). */
      std::vector<std::pair<SlaveNode<dim>, bool>>
      active_set_snapshot() const
      {
        return contact->active_set_snapshot();
      }

      /** Warm-start the next solve from another state's active set: each
       * node takes the flag of the nearest node of that state on the same
       * disc and pin. */
      void
      warm_start(const std::vector<std::pair<SlaveNode<dim>, bool>> &snapshot)
      {
        contact->transfer_active_set(snapshot);
        warm = !snapshot.empty();
      }

      /** Print the timing summary of this object's stages (rank 0). */
      void
      print_timing() const
      {
        timer.print_summary();
      }

      /** Write solution-NNNN.pvtu for state @p step and rewrite
       * solution.pvd (the record lists every state written by this
       * object and @p previous). */
      void
      output_results(const unsigned int                           step,
                     std::vector<std::pair<double, std::string>> &records);

    protected:
      void
      make_grid();
      void
      setup_system();
      ContactState
      solve_state(const double load);
      void
      refine_at_contacts();
      void
      pin_forces(const double                           torque,
                 const ContactState                    &state,
                 postprocess::StiffnessRow             &row,
                 std::vector<postprocess::PinForceRow> &pins) const;

      /** Force scale from the model to the stage: b in 2D, 1 in 3D. */
      double
      width_scale() const;

      const parameters::AllParameters prm;
      const MPI_Comm                  comm;
      double                          psi;
      /** Crank angle of the mesh (psi differs in transient runs). */
      const double                                 psi_mesh;
      const double                                 sweep;
      const geometry::CycloidGeometry              geo;
      dealii::ConditionalOStream                   pcout;
      mutable dealii::TimerOutput                  timer;
      dealii::parallel::shared::Triangulation<dim> tria;
      std::unique_ptr<PinModel<dim>>               pin_model;
      std::unique_ptr<ContactProblem<dim>>         contact;
      bool                                         warm = false;
    };
  } // namespace contact
} // namespace cycloid

#endif

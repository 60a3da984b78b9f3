#ifndef cycloid_dynamics_contact_dynamics_h
#define cycloid_dynamics_contact_dynamics_h

#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/contact/contact_problem.h>
#include <cycloid/dynamics/checkpoint.h>
#include <cycloid/dynamics/time_scheme.h>
#include <cycloid/dynamics/transient_parameters.h>

#include <iosfwd>
#include <map>
#include <memory>
#include <set>
#include <string>

namespace cycloid
{
  namespace dynamics
  {
    /** Settings of ContactDynamics. */
    struct DynamicsSettings
    {
      /** The time scheme (`Transient/Scheme`; see create_time_scheme()). */
      Scheme scheme = Scheme::contact_stabilised;
      /** rho_inf of generalized-alpha [-]. */
      double spectral_radius = 0.8;
      /** Rayleigh damping C = a M + b K: a [1/s]. */
      double rayleigh_mass = 0.;
      /** Rayleigh damping C = a M + b K: b [s]. */
      double rayleigh_stiffness = 0.;
    };

    /** What one time step did; energies in N mm (per mm thickness in 2D),
     * accumulated from t = 0. */
    struct StepReport
    {
      /** The contact solve of the end-of-step state (beta, reaction). */
      contact::ContactState state;
      /** Active-set iterations of the step (projection included). */
      unsigned int iterations = 0;
      double       elastic    = 0; ///< Elastic energy at t_{n+1}.
      double       kinetic    = 0; ///< Kinetic energy at t_{n+1}.
      /** Work of the load surface (torque or prescribed rotation). */
      double bore_work = 0;
      /** Work of the moving obstacles: -sum lambda [G_{n+1}(u_mid) -
       * G_n(u_mid)] over the contact nodes, G the gap function of each time
       * level at the mid-step displacement (zero for fixed obstacles);
       * lambda the step's force: (lambda_n + lambda_{n+1})/2 for Newmark,
       * the step average of contact-stabilised, the alpha-level force of
       * generalized-alpha. The contact-stabilised projection's own work on
       * moving obstacles is not part of it. */
      double contact_work = 0;
      /** Rayleigh damping dissipation. */
      double dissipated = 0;
      /** Largest penetration of a slave node at the end of the step [mm]
       * (0 if none). */
      double max_penetration = 0;
    };

    /**
     * @brief Elastodynamics M a + C v + K u = r (contact) on a
     * contact::ContactProblem, one implicit step at a time.
     *
     * Each step is one or more contact problems with the effective
     * operator A = s_K K + s_M M and the history load
     * (elasticity::DynamicTerms) of the TimeScheme that
     * DynamicsSettings::scheme names (create_time_scheme()); the primal-dual
     * active set of ContactProblem solves them, warm-started from the
     * previous step, with the load surface either torque-controlled
     * (two-solve superposition) or rotation-controlled. What every scheme
     * shares stays here: the state (u, v, a, beta) and the energy accounts
     * persist between steps and can be saved and restored
     * (checkpoint/restart on the same number of ranks).
     *
     * Energy balance: E_kin + E_el - W_load - W_contact + D = E_0, with
     * W_load the trapezoidal work of the load surface, W_contact the work of
     * moving obstacles (-lambda d gap0, zero for fixed ones) and D the
     * Rayleigh dissipation.
     */
    template <int dim>
    class ContactDynamics
    {
    public:
      /** On @p contact (set up, with fixed DoFs and load pattern). */
      ContactDynamics(contact::ContactProblem<dim> &contact,
                      const DynamicsSettings       &settings);

      /**
       * Start at rest and undeformed, or with velocity @p v0 (ghosted;
       * empty: at rest). The initial acceleration is -a v0 (exact for a
       * rigid-body initial velocity, which is what the drivers use).
       */
      void
      initialise(const dealii::TrilinosWrappers::MPI::Vector &v0 =
                   dealii::TrilinosWrappers::MPI::Vector());

      /**
       * Advance by @p dt. Torque control (@p load_control) with @p value
       * the load at the end of the step (in the units of
       * ContactProblem::solve_load), else rotation control with @p value the
       * rotation beta at the end of the step. Call
       * ContactProblem::update_geometry() before, if the obstacles moved.
       */
      StepReport
      step(const double       dt,
           const bool         load_control,
           const double       value,
           const std::string &label);

      /** Displacement at the current time (ghosted) [mm]. */
      const dealii::TrilinosWrappers::MPI::Vector &
      displacement() const
      {
        return u;
      }

      /** Velocity at the current time (ghosted) [mm/s]. */
      const dealii::TrilinosWrappers::MPI::Vector &
      velocity() const
      {
        return v;
      }

      /**
       * Write the state (owned entries of this rank) to a checkpoint, or
       * restore it from one written on the same mesh and ranks: the one
       * list of its fields (CheckpointArchive).
       */
      void
      checkpoint(CheckpointArchive &ar);

    private:
      /** The contact record's entries, through @p ar (checkpoint()). */
      void
      checkpoint_record(CheckpointArchive &ar);

      /** The first DoF of each active slave node. */
      std::set<dealii::types::global_dof_index>
      active_dofs() const;

      /** The contact constraints of the current state with their normal
       * forces, by the slave's first DoF: for the work of moving obstacles. */
      std::map<dealii::types::global_dof_index,
               std::pair<double, contact::SlaveNode<dim>>>
      contact_record() const;

      /** Work of moving obstacles from the old record to the current
       * constraints, at the mid-step displacement @p u_mid (owned). */
      double
      obstacle_work(const dealii::TrilinosWrappers::MPI::Vector &u_mid,
                    const std::map<dealii::types::global_dof_index,
                                   std::pair<double, contact::SlaveNode<dim>>>
                      &new_record) const;

      contact::ContactProblem<dim> &contact;
      const DynamicsSettings        settings;
      const MPI_Comm                comm;
      /** The scheme of settings.scheme; it holds no state, so copies of
       * this object share it. */
      const std::shared_ptr<const TimeScheme<dim>> scheme;

      dealii::TrilinosWrappers::MPI::Vector u, v, a;
      double                                beta = 0, beta_old = 0;
      double                                applied = 0;
      double                                dt_old  = 0;
      StepReport                            totals;
      std::map<dealii::types::global_dof_index,
               std::pair<double, contact::SlaveNode<dim>>>
        record;
    };
  } // namespace dynamics
} // namespace cycloid

#endif

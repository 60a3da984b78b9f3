#ifndef cycloid_dynamics_time_scheme_h
#define cycloid_dynamics_time_scheme_h

#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/contact/contact_problem.h>

#include <memory>
#include <string>

namespace cycloid
{
  namespace dynamics
  {
    struct DynamicsSettings;

    /** Where a time step starts (t_n) and what it must reach (t_{n+1}). */
    struct StepInput
    {
      /** Displacement at t_n (owned) [mm]. */
      const dealii::TrilinosWrappers::MPI::Vector &u;
      /** Velocity at t_n (owned) [mm/s]. */
      const dealii::TrilinosWrappers::MPI::Vector &v;
      /** Acceleration at t_n (owned) [mm/s^2]. */
      const dealii::TrilinosWrappers::MPI::Vector &a;
      /** Rotation of the load surface at t_n [rad]. */
      double beta;
      /** Force of the load surface at t_n: the load (torque control) or the
       * reaction (rotation control) of the previous step. */
      double applied;
      /** Time step [s]. */
      double dt;
      /** Torque control (else rotation control). */
      bool load_control;
      /** Load (torque control) or rotation (rotation control) at t_{n+1}. */
      double value;
      /** Label of the step in the solver's messages. */
      const std::string &label;
    };

    /** What the scheme's step produced: the state at t_{n+1}. */
    struct StepOutcome
    {
      /** The contact solve of the end-of-step state, its reaction the
       * load surface's force at t_{n+1} and its linear iterations those of
       * every solve of the step. */
      contact::ContactState state;
      /** Active-set iterations of every solve of the step. */
      unsigned int iterations = 0;
      /** Displacement at t_{n+1} (owned) [mm]. */
      dealii::TrilinosWrappers::MPI::Vector u;
      /** Velocity at t_{n+1} (owned) [mm/s]. */
      dealii::TrilinosWrappers::MPI::Vector v;
      /** Acceleration at t_{n+1} (owned; zero where the scheme does not
       * carry it) [mm/s^2]. */
      dealii::TrilinosWrappers::MPI::Vector a;
    };

    /**
     * @brief The scheme-specific part of a time step of ContactDynamics:
     * the swappable part chosen by `Transient/Scheme` (create_time_scheme()).
     *
     * A scheme turns the state at t_n into contact problems with its
     * effective operator and history loads (elasticity::DynamicTerms),
     * solves them on the ContactProblem, and updates u, v, a from the
     * solution; it also says which contact force of the step does work on
     * moving obstacles. The energy accounts, the state between steps and
     * checkpoints stay with ContactDynamics, which is the same for every
     * scheme. A scheme holds no state of its own beyond its coefficients,
     * so one object can serve any number of steps (and copies of the
     * facade).
     */
    template <int dim>
    class TimeScheme
    {
    public:
      virtual ~TimeScheme() = default;

      /**
       * One step from @p in on @p contact: set the dynamic terms, solve,
       * and return the state at t_{n+1}. The reactions that @p contact
       * stores afterwards are the forces this scheme reports for the step
       * (obstacle_force() reads them); the dynamic terms are left set (the
       * caller clears them, for every scheme alike).
       */
      virtual StepOutcome
      step(contact::ContactProblem<dim> &contact,
           const StepInput              &in) const = 0;

      /**
       * The contact force of one node that does work on a moving obstacle
       * during the step, from the normal forces @p old_force and
       * @p new_force that contact reported after the previous and after
       * this step.
       */
      virtual double
      obstacle_force(const double old_force, const double new_force) const = 0;
    };

    /** The scheme of @p settings (its coefficients from the spectral
     * radius and the Rayleigh damping there). */
    template <int dim>
    std::unique_ptr<TimeScheme<dim>>
    create_time_scheme(const DynamicsSettings &settings);

    /** The owned entries of @p x (e.g. the ghosted displacement of a
     * solve), in the layout the schemes compute in. */
    template <int dim>
    dealii::TrilinosWrappers::MPI::Vector
    owned_copy(const contact::ContactProblem<dim>          &contact,
               const dealii::TrilinosWrappers::MPI::Vector &x);

    /** @p x (owned) with the ghost entries of @p contact's DoFs, as the
     * dynamic terms and the energies read it. */
    template <int dim>
    dealii::TrilinosWrappers::MPI::Vector
    ghosted(const contact::ContactProblem<dim>          &contact,
            const dealii::TrilinosWrappers::MPI::Vector &x);
  } // namespace dynamics
} // namespace cycloid

#endif

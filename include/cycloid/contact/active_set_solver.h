#ifndef cycloid_contact_active_set_solver_h
#define cycloid_contact_active_set_solver_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/contact/constraint_formulation.h>
#include <cycloid/contact/contact_schur.h>
#include <cycloid/contact/contact_types.h>
#include <cycloid/elasticity/elasticity.h>

#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief What a load state is solved on, owned by the caller (e.g.
     * ContactProblem): the discretised contact nodes, the tied nodes, the
     * fixed DoFs and the load pattern (DoFs moved by beta * g).
     */
    template <int dim>
    struct ContactSystem
    {
      /** Slave nodes with their normals and master coefficients. */
      const std::vector<SlaveNode<dim>> &slaves;
      /** Tied nodes. */
      const std::vector<TiedNode<dim>> &ties;
      /** DoFs held at zero. */
      const std::vector<dealii::types::global_dof_index> &fixed;
      /** DoFs moved by beta * g and their g. */
      const std::map<dealii::types::global_dof_index, double> &load;
      /** Owned cells at the slave and load DoFs: the solver reads nodal
       * forces there only, so it sums them over these cells (null: all
       * cells). */
      const typename elasticity::LinearElasticity<dim>::CellList *force_cells =
        nullptr;
      /** On a distributed mesh: the hanging-node lines of the ghosted
       * master DoFs, from the ranks that own them (a rank may not hold
       * the cells that make a master DoF hang); null: none. */
      const dealii::AffineConstraints<double> *master_hanging = nullptr;

      /** Add the supports of every state to @p c: the masters' hanging
       * lines this rank cannot build (master_hanging), the fixed DoFs, the
       * load DoFs at beta * g and the ties (DoFs already constrained, e.g.
       * by hanging nodes, keep their constraint). */
      void
      add_supports(dealii::AffineConstraints<double> &c,
                   const double                       beta) const;
    };

    /**
     * @brief The primal-dual active set (semi-smooth Newton, Hueber-
     * Wohlmuth) of one load state; see ContactProblem for the method.
     *
     * Per iteration, for the current set: the constraints and the matrix
     * with two right-hand sides (gaps, unit load), the preconditioner, the
     * two solves u0, u1 (for a fixed set u = u0 + beta u1), the beta that
     * meets the load (load control) or the given beta, and the next set
     * from the nodal reactions and gaps. While the set changes, the solves
     * stop at ContactSettings::inner_tolerance, each next one ten times
     * tighter down to loose_floor (they only
     * decide the next set); once it repeats, the same system is solved again to
     * solver_tolerance and the set checked once more, so the reported state
     * is a tight solution. A set that moved by at most 1 % of its nodes is
     * solved tight at once, and so is every set of a time step (a mass
     * term). `iterations` counts the sets assembled. If a
     * timer is given, these stages
     * are timed in its sections "contact: constraints and assembly",
     * "contact: preconditioner", "contact: linear solves", "contact:
     * active-set update" and, once per state, "contact: residual and
     * reactions". Every stage is collective, so the sections are entered
     * on all ranks alike. The environment variable CYCLOID_DEBUG prints
     * each iteration's times, set sizes and rank 0's memory (resident
     * after each stage, heap in use, peak) to stderr.
     *
     * One object per load state: it holds the state's solutions, which
     * warm-start CG in the next iteration.
     */
    template <int dim>
    class ActiveSetSolver
    {
    public:
      /** Solve on @p problem (its DoFs distributed) for @p system,
       * constrained as @p formulation says; all held by reference.
       * @p timer may be null (nothing timed). With @p schur, each set is
       * solved through the Schur complement of its contact rows on the
       * operator that @p schur keeps factorised (ContactSchur) instead of
       * a matrix condensed and factorised per set. */
      ActiveSetSolver(elasticity::LinearElasticity<dim> &problem,
                      const ConstraintFormulation<dim>  &formulation,
                      const ContactSettings             &settings,
                      const ContactSystem<dim>          &system,
                      dealii::TimerOutput               *timer,
                      ContactSchur<dim>                 *schur = nullptr);

      /**
       * Iterate from the active set in @p solution until it repeats, for
       * the generalised reaction @p value (@p load_control) or for beta =
       * @p value. On return @p solution holds the converged set, the slave
       * reactions and gaps and the displacement. Throws, naming @p label,
       * at the iteration limit, on cycling, if no node carries the load
       * or if the equilibrium residual is above the tolerance.
       */
      ContactState
      solve(const bool            load_control,
            const double          value,
            const std::string    &label,
            ContactSolution<dim> &solution);

    private:
      /** The constraints of set @p active: fixed DoFs, the load beta * g,
       * ties and active nodes (their gaps if @p with_gaps). */
      std::function<void(dealii::AffineConstraints<double> &)>
      constraint_set(const std::set<unsigned int> &active,
                     const bool                    with_gaps,
                     const double                  beta) const;

      /** Constraints, matrix and both right-hand sides for @p active. */
      void
      assemble(const std::set<unsigned int> &active);

      /** The contact lines of the nodes of @p active (with their gaps). */
      std::function<void(dealii::AffineConstraints<double> &)>
      contact_lines(const std::set<unsigned int> &active) const;

      /** Hand the state to schur (assembly and factorisation of the
       * supports alone, the solutions without contact); false if it
       * cannot take it (then the state is condensed per set). */
      bool
      begin_schur(ContactState &state);

      /** Build the preconditioner of the new matrix, or keep the one
       * LinearElasticity::setup_preconditioner() keeps. */
      void
      setup_preconditioner();

      /**
       * The linear part of one active-set iteration on the set @p active:
       * its constraints and matrix (unless @p assembled, the set of the
       * previous iteration), the preconditioner, and u0 and u1 (to the
       * relative @p tolerance, or exactly through the Schur complement);
       * counts the iteration and the preconditioner set-ups in @p state.
       * With CYCLOID_DEBUG set, rank 0 prints where time and memory went,
       * headed by @p iteration.
       */
      void
      solve_iterate(const std::set<unsigned int> &active,
                    const bool                    assembled,
                    const double                  tolerance,
                    const std::string            &iteration,
                    ContactState                 &state);

      /** u0 (gaps, no load) and u1 (unit load) to the relative
       * @p tolerance, warm-started from the previous iteration's. */
      void
      solve_linear_systems(const double tolerance, ContactState &state);

      /** Nodal forces of u0 and u1, their generalised reactions Q0, Q1
       * and the beta of the state (the superposition u0 + beta u1). A
       * load-controlled iterate whose set is empty (@p free) and whose beta
       * has the wrong sign or passes the first_closure() takes the latter
       * instead (a beta short of it, as in a transient step, stays). */
      void
      superpose(const bool         load_control,
                const double       value,
                const std::string &label,
                const bool         free,
                ContactState      &state);

      /** The smallest |beta| in the direction of the load @p value at
       * which a node's gap closes, times (1 + 1e-6) plus 1e-12 so that
       * the nodes closing first (and their ties, and a node touching at
       * beta = 0) enter the next set; NaN if no node
       * closes in that direction. For an empty set under load control,
       * where (value - Q0) / Q1 divides by the body's vanishing resistance
       * and pushes nearly every node in at once (measured: an active set
       * that then shrinks back to empty, a cycle). */
      double
      first_closure(const double value) const;

      /** What the update from one set to the next saw, over all ranks. */
      struct SetChange
      {
        /** The largest normal force at an active node [N; per mm in 2D]. */
        double largest_force = 0;
        /** The largest tension (minus the normal force) at an active node
         * that leaves [N; per mm in 2D]. */
        double largest_tension = 0;
        /** Whether an inactive node penetrates (and enters). */
        bool entering = false;
      };

      /** The next active set from the reactions and gaps of u0 + beta u1
       * (gathered over the ranks), every node's gap in @p gaps and what
       * changed in @p change. */
      std::set<unsigned int>
      next_active_set(const std::set<unsigned int> &active,
                      const double                  beta,
                      std::vector<double>          &gaps,
                      SetChange                    &change) const;

      /** The nodes in one of @p active and @p next but not in both. */
      static std::size_t
      n_moved(const std::set<unsigned int> &active,
              const std::set<unsigned int> &next);

      /** Record @p active and move on to @p next (a new set). If @p next
       * was seen before: with loose solves, switch to @p tight ones (a
       * node at the threshold may have been misjudged); with tight ones,
       * move on to the union of the cycle's sets instead and return true
       * (a cycle), once: a second cycle throws. */
      bool
      settle(std::set<unsigned int>              &active,
             const std::set<unsigned int>        &next,
             std::vector<std::set<unsigned int>> &history,
             const unsigned int                   iteration,
             const std::string                   &label,
             bool                                &tight) const;

      /** After a cycle, the union of its sets was solved and gave
       * @p change: accept it (count it in @p state) if no node penetrates
       * and no node is in tension above cycle_tension_limit of the largest
       * force; else throw, naming @p label. */
      void
      accept_cycle_union(const SetChange   &change,
                         const std::string &label,
                         ContactState      &state) const;

      /** The largest tension accepted at a node of a broken cycle's union,
       * relative to the largest nodal contact force. The cycles measured
       * (consistent-mass projections of the contact-stabilised scheme,
       * doc/stability.md §4c) left 0; a tension this small moves a pin
       * force by less than 1e-3 of a nodal force. */
      static constexpr double cycle_tension_limit = 1e-3;

      /** The factor on the CG tolerance of the solve of a cycle's union. */
      static constexpr double cycle_tightening = 1e-2;

      /** The factor from one loose solve's tolerance to the next one's in
       * a state. The first loose solve only has to find the bulk of the
       * set; the later ones decide the nodes at the edge of a contact,
       * whose forces are small, so they solve tighter (measured:
       * doc/solver-reuse.md, "A loose solve that tightens"). */
      static constexpr double loose_tightening = 0.1;

      /** The tolerance the loose solves tighten to, unless
       * ContactSettings::inner_tolerance is tighter already: from there
       * on a loose solve decides the nodes at the edge of a contact as a
       * tight one does (a constant 1e-6 never took more sets than tight
       * solves in the cases measured). */
      static constexpr double loose_floor = 1e-6;

      /** The state's displacement, equilibrium residual (checked) and
       * slave reactions. */
      void
      finish(const std::string    &label,
             ContactState         &state,
             ContactSolution<dim> &solution) const;

      /** Start u0 and u1 from @p solution's last state under the same
       * operator, if there is one. */
      void
      warm_start(const ContactSolution<dim> &solution);

      /** Keep u0 and u1 in @p solution as the next state's start. */
      void
      keep_start(ContactSolution<dim> &solution) const;

      /** Generalised reaction sum_d g_d f_d of the load pattern. */
      double
      reaction(const dealii::TrilinosWrappers::MPI::Vector &f) const;

      elasticity::LinearElasticity<dim> &problem;
      const ConstraintFormulation<dim>  &formulation;
      const ContactSettings             &settings;
      const ContactSystem<dim>           system;
      dealii::TimerOutput *const         timer;
      /** The kept factorisation, or null (see the constructor). */
      ContactSchur<dim> *const schur;
      /** Whether this state's sets go through schur. */
      bool           use_schur = false;
      const MPI_Comm comm;
      /** Print each iteration to stderr (CYCLOID_DEBUG set, rank 0). */
      const bool verbose;

      /** The two solutions of the current set and their nodal forces. */
      dealii::TrilinosWrappers::MPI::Vector u0, u1, f0, f1;
      /** Generalised reactions of u0 and u1. */
      double q0 = 0, q1 = 0;
      /** Wall time of the current iteration's stages (CYCLOID_DEBUG). */
      dealii::Timer clock;
      /** Iterations of the current iteration's two solves. */
      unsigned int n0 = 0, n1 = 0;
    };
  } // namespace contact
} // namespace cycloid

#endif

#ifndef cycloid_contact_contact_parameters_h
#define cycloid_contact_contact_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <cycloid/contact/contact_types.h>
#include <cycloid/elasticity/elasticity.h>

#include <algorithm>
#include <optional>
#include <string>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief Subsections `Contact` (active-set method) and `Solver` (linear
     * solver of each active-set iteration).
     */
    struct ContactParameters
    {
      /** Iteration limit of the active set per load state. */
      unsigned int max_active_set_iterations = 100;
      /** Flank vertices closer than this to a pin surface are contact
       * candidates [mm]. */
      double search_distance = 0.1;
      /** Constraint discretisation (`Formulation`: mortar or
       * node-to-surface). */
      Formulation formulation = Formulation::mortar;
      /** Where the first state's active set starts (`First active
       * set`). */
      FirstActiveSet first_set = FirstActiveSet::hertz;
      /** Largest accepted relative equilibrium residual [-]. */
      double residual_tolerance = 1e-6;
      /** Linear solver (`Linear solver`: cg-amg, cg-amg-translations or
       * direct). */
      elasticity::LinearSolver linear_solver = elasticity::LinearSolver::cg_amg;
      /** `Direct solver`: as set, or absent for auto (see
       * factorisation()). */
      std::optional<elasticity::Factorisation> direct_solver;
      /** `AMG hierarchy`: as set, or absent for auto (see hierarchy()). */
      std::optional<elasticity::AMGHierarchy> amg_hierarchy;
      /** Relative tolerance of the iterative solver [-]. */
      double solver_tolerance = 1e-10;
      /** Marks `Inner tolerance = auto`. */
      static constexpr double automatic = -1;
      /** Relative tolerance of the iterative solver while the active set
       * still changes (`Inner tolerance`) [-]; automatic: see
       * inner(). */
      double inner_tolerance = automatic;
      /** Keep the pattern and the AMG hierarchy over active sets, states
       * and time steps (`Preconditioner reuse`). */
      bool reuse_preconditioner = false;
      /** `Contact Schur complement`: true, false, or automatic (absent:
       * auto). */
      std::optional<bool> schur_complement;
      /** `Contact Schur complement columns`. */
      unsigned int schur_columns = 4000;

      /** Whether the contact rows go through their Schur complement on a
       * kept factorisation (contact::ContactSchur): as set, or under auto
       * when the solver is direct and the run solves its states on one
       * operator (@p one_operator: a time step of Newmark or
       * generalized-alpha at a fixed step, where one factorisation serves
       * the whole run). */
      bool
      use_schur_complement(const bool one_operator) const
      {
        if (linear_solver != elasticity::LinearSolver::direct)
          return false;
        return schur_complement.value_or(one_operator);
      }

      /** The inner tolerance of a scene of dimension @p dim, the first
       * loose solve's of a state: auto is 1e-4 in 3D, where a state's CG
       * iterations are its cost (the 3D seed case takes 0.78 of the CG
       * iterations and 0.69-0.80 of the time of a constant 1e-6), and
       * tight in 2D, where a loose final start upset a 1e-8 torque
       * balance (doc/solver-reuse.md). */
      double
      inner(const unsigned int dim) const
      {
        return std::max(inner_tolerance == automatic ? (dim == 3 ? 1e-4 : 0.) :
                                                       inner_tolerance,
                        solver_tolerance);
      }

      /** The AMG hierarchy of a scene of dimension @p dim: auto is plain
       * aggregation with a W-cycle in 3D, where the smoothed hierarchy's
       * set-up and size dominate a state's memory, and smoothed with a
       * V-cycle in 2D (doc/solver-reuse.md). */
      elasticity::AMGHierarchy
      hierarchy(const unsigned int dim) const
      {
        return amg_hierarchy.value_or(dim == 3 ?
                                        elasticity::AMGHierarchy::plain_w :
                                        elasticity::AMGHierarchy::smoothed_v);
      }

      /** The factorisation of a direct solve: as set, else CHOLMOD's
       * simplicial Cholesky, except for the reduced model's condensation
       * (@p condensation) of a 3D scene (@p dim): MUMPS's L D L^T, whose
       * condensation of the seed case took 8.7 s against CHOLMOD
       * supernodal's 21.7 s, on 2 ranks (doc/solver-reuse.md). */
      elasticity::Factorisation
      factorisation(const unsigned int dim, const bool condensation) const
      {
        return direct_solver.value_or(condensation && dim == 3 ?
                                        elasticity::Factorisation::mumps :
                                        elasticity::Factorisation::cholmod);
      }

      /** Declare subsections `Contact` and `Solver`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsections `Contact` and `Solver`. */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace contact
} // namespace cycloid

#endif

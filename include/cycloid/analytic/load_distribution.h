#ifndef cycloid_analytic_load_distribution_h
#define cycloid_analytic_load_distribution_h

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <cycloid/analytic/pair_stiffness.h>
#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/support/crank_supports.h>

#include <array>
#include <functional>
#include <vector>

namespace cycloid
{
  namespace analytic
  {
    /**
     * @brief One pin-disc pair in a solved load state.
     */
    struct PinLoad
    {
      /** Unloaded contact geometry. */
      geometry::PinContact contact;
      /** Geometry seen by the pair model. */
      PairGeometry pair;
      /** Approach beta * arm - clearance, clipped at 0 [mm]. */
      double approach = 0;
      /** Normal force of the pin on the disc [N]. */
      double force = 0;
      /** Pair stiffness dF/d approach [N/mm]. */
      double stiffness = 0;
    };

    /**
     * @brief A solved load state of the analytical model.
     */
    struct LoadState
    {
      /** Target output torque [N m]. */
      double torque = 0;
      /** Rotation beta of the discs from the kinematic position [rad]. */
      double rotation = 0;
      /** Rigid take-up rotation that closes the smallest clearance on the
       * loaded side (lost motion) [rad]. */
      double takeup = 0;
      /** Reaction torque sum F * arm [N m] (equals torque at
       * convergence). */
      double reaction_torque = 0;
      /** Tangent stiffness dT/dbeta = sum k l^2 [N m/rad]. */
      double k_tangent = 0;
      /** Number of pins carrying force (over all discs). */
      unsigned int pins_in_contact = 0;
      /** Iterations of the torque-balance solve. */
      unsigned int iterations = 0;
      /** Every pin of every disc. */
      std::vector<PinLoad> pins;
      /** Each disc's rigid motion on its crank bearings (empty on rigid
       * supports, where each disc turns by the rotation). */
      std::vector<support::DiscMotion> motions;
      /** Every crank bearing of every disc (empty on rigid supports). */
      std::vector<results::BearingState> bearings;
      /** Where the rotation comes from. */
      results::ComplianceBreakdown breakdown;

      /** Secant stiffness T / beta [N m/rad]. */
      double
      k_secant() const;
      /** Secant stiffness after the take-up, T / (beta - takeup)
       * [N m/rad]. */
      double
      k_secant_elastic() const;
    };

    /**
     * @brief Load distribution over the pins of one or two discs that share
     * one rotation beta (they drive one output carrier): find beta such
     * that the pins whose approach beta * l_i exceeds their clearance carry
     * F_i = F(beta l_i - c_i) and sum_i F_i l_i = T.
     *
     * The torque sum_i F_i(beta l_i - c_i) l_i is continuous and
     * non-decreasing in beta, so a bracket from the take-up rotation plus a
     * safeguarded Newton iteration (slope sum k_i l_i^2) converges for any
     * pair model with non-decreasing F. On crank bearings the discs also
     * translate and turn against them (solve() with a
     * support::CrankSupports, DiscEquilibrium).
     */
    class LoadDistribution
    {
    public:
      /** Keeps a reference to @p model. */
      LoadDistribution(const PairStiffnessModel &model,
                       const double              relative_tolerance,
                       const unsigned int        max_iterations);

      /**
       * Solve for output torque @p torque [N m] given the unloaded pin
       * geometry @p pins (their `pair` set) and a warm-start guess of beta
       * (0: none). Throws with a clear message if it does not converge.
       */
      LoadState
      solve(const std::vector<PinLoad> &pins,
            const double                torque,
            const double                beta_guess = 0.) const;

      /**
       * The same on the crank bearings @p supports: each disc translates
       * and turns against its bearings until it is in equilibrium
       * (DiscEquilibrium) at every rotation beta of the eccentrics, and beta
       * carries the torque. The bearings' clearance adds to the take-up.
       */
      LoadState
      solve(const std::vector<PinLoad>   &pins,
            const double                  torque,
            const double                  beta_guess,
            const support::CrankSupports &supports) const;

      /**
       * The limit of the load state as the torque goes to zero from side
       * @p side (+1 or -1): beta is the signed take-up rotation, every pin
       * just touching or clear, no force. (A frictionless stage at zero
       * torque may rest anywhere between the two limits.)
       */
      LoadState
      zero_torque_limit(const std::vector<PinLoad> &pins, const int side) const;

      /** The same on the crank bearings @p supports: the take-up is the
       * largest rotation at which the discs, free in their bearings'
       * clearance, still carry no torque. */
      LoadState
      zero_torque_limit(const std::vector<PinLoad>   &pins,
                        const int                     side,
                        const support::CrankSupports &supports) const;

    private:
      /** Torque [N mm] and slope [N mm/rad] at rotation beta, filling the
       * per-pin state. */
      double
      torque_at(const double          beta,
                std::vector<PinLoad> &pins,
                double               &slope) const;

      /** The rotation x (sign * beta) that carries @p goal [N mm] of
       * sign @p sign from take-up @p takeup, @p torque_of(beta, slope)
       * the torque [N mm] at beta: a bracket and a safeguarded Newton
       * iteration. Returns x; @p slope [N mm/rad] and @p iterations at it. */
      double
      carrying_rotation(
        const std::function<double(double, double &)> &torque_of,
        const double                                   goal,
        const double                                   sign,
        const double                                   takeup,
        const double                                   beta_guess,
        double                                        &slope,
        unsigned int                                  &iterations) const;

      const PairStiffnessModel &model;
      const double              tolerance;
      const unsigned int        max_iterations;
    };

    /**
     * @brief The stage on its crank bearings: the rotation beta of the
     * eccentrics and each disc's motion q_d = (t_d, theta_d) such that each
     * disc's pins, F_i = F(n_i . t_d + theta_d l_i - c_i), and its bearings
     * (support::CrankSupports) balance in force and moment, and the pins
     * carry the torque, sum F_i l_i = T. One Newton iteration over all
     * 3 n_discs + 1 unknowns with a backtracking line search: with the
     * torque imposed the forces never all vanish, so no state floats in
     * its clearances (a rotation imposed instead would leave a disc free
     * in them, and the iteration slow), and the laws being powers of the
     * approach, the iteration converges alike at any load.
     */
    class DiscEquilibrium
    {
    public:
      /** Keeps references to @p model and @p supports. */
      DiscEquilibrium(const PairStiffnessModel     &model,
                      const support::CrankSupports &supports,
                      const double                  tolerance,
                      const unsigned int            max_iterations);

      /** The solution for torque @p torque [N mm]. */
      struct Solution
      {
        /** Rotation beta [rad]. */
        double rotation = 0;
        /** dT/dbeta [N mm/rad]. */
        double slope = 0;
        /** Each disc's motion. */
        std::vector<support::DiscMotion> motions;
        /** Newton iterations. */
        unsigned int iterations = 0;
      };

      /** Solve for @p torque [N mm] from rotation @p beta_guess [rad] and
       * the disc motions @p start (empty: each disc turned by
       * @p beta_guess); @p pins' forces at the solution. Throws if it does
       * not converge. */
      Solution
      solve(const double                            torque,
            const double                            beta_guess,
            const std::vector<support::DiscMotion> &start,
            std::vector<PinLoad>                   &pins) const;

    private:
      /** Residual (each disc's force and moment, the torque) and
       * Jacobian in ((t_x, t_y, theta) per disc, beta) at @p x; @p pins'
       * forces filled; bearings with none loaded @p floor stiff per
       * roller. */
      void
      system(const dealii::Vector<double> &x,
             const double                  torque,
             const double                  floor,
             std::vector<PinLoad>         &pins,
             dealii::Vector<double>       &r,
             dealii::FullMatrix<double>   &J) const;

      /** The residual's size, a moment counted as a force at the crank
       * circle. */
      double
      merit(const dealii::Vector<double> &r) const;

      /** The gradient @p g and Hessian @p H of energy() at @p x (the
       * Hessian guarded as system()'s Jacobian is). */
      void
      gradient(const dealii::Vector<double> &x,
               const double                  torque,
               const double                  floor,
               std::vector<PinLoad>         &pins,
               dealii::Vector<double>       &g,
               dealii::FullMatrix<double>   &H) const;

      /** The largest of the residual @p r's parts against the stage's
       * largest force, moment and @p torque [-]. */
      double
      relative_residual(const dealii::Vector<double> &r,
                        const double                  torque,
                        const std::vector<PinLoad>   &pins) const;

      /** One guarded Newton step on the energy from @p x (in place), with
       * an Armijo line search (or, below the energy's round-off, a smaller
       * residual than @p r); false if no step moves. */
      bool
      newton_step(dealii::Vector<double>       &x,
                  const double                  torque,
                  const double                  floor,
                  std::vector<PinLoad>         &pins,
                  const dealii::Vector<double> &r) const;

      /** dT/dbeta at the solution @p x [N mm/rad]. */
      double
      tangent(const dealii::Vector<double> &x,
              const double                  torque,
              const double                  floor,
              std::vector<PinLoad>         &pins) const;

      /** The energy of pins and bearings minus the torque's work T beta
       * at @p x [N mm]: the solution is its minimum. */
      double
      energy(const dealii::Vector<double> &x,
             const double                  torque,
             const std::vector<PinLoad>   &pins) const;

      const PairStiffnessModel     &model;
      const support::CrankSupports &supports;
      const double                  tolerance;
      const unsigned int            max_iterations;
    };
  } // namespace analytic
} // namespace cycloid

#endif

#ifndef cycloid_analytic_load_distribution_h
#define cycloid_analytic_load_distribution_h

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
     * pair model with non-decreasing F.
     */
    class DiscEquilibrium;

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
      solve(const std::vector<PinLoad>    &pins,
            const double                   torque,
            const double                   beta_guess,
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
      zero_torque_limit(const std::vector<PinLoad>    &pins,
                        const int                      side,
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
     * @brief Each disc in equilibrium on its crank bearings at a rotation
     * beta of the eccentrics: the disc motion q = (t, theta) such that its
     * pins, F_i = F(n_i . t + theta l_i - c_i), and its bearings
     * (support::CrankSupports) balance in force and moment. The energy is
     * convex in q, so a Newton iteration with a backtracking line search
     * finds it; the torque T(beta) = sum F_i l_i it gives is
     * non-decreasing in beta, with dT/dbeta from the implicit function.
     */
    class DiscEquilibrium
    {
    public:
      /** Keeps references to @p model and @p supports. */
      DiscEquilibrium(const PairStiffnessModel     &model,
                      const support::CrankSupports &supports,
                      const double                  tolerance,
                      const unsigned int            max_iterations,
                      const double                  floor);

      /** The torque [N mm] at rotation @p beta [rad], its slope @p slope
       * [N mm/rad]; @p pins' forces and @p motions (the warm start, one per
       * disc) at equilibrium. */
      double
      torque_at(const double                      beta,
                std::vector<PinLoad>             &pins,
                std::vector<support::DiscMotion> &motions,
                double                           &slope) const;

    private:
      /** Residual (force, moment of pins and bearings on disc @p d) and
       * its 3 x 4 derivative in (t_x, t_y, theta, beta), @p pins' forces
       * filled; bearings at least @p floor stiff per roller. */
      std::array<double, 3>
      residual(const unsigned int          d,
               const support::DiscMotion  &q,
               const double                beta,
               const double                floor,
               std::vector<PinLoad>       &pins,
               dealii::FullMatrix<double> &derivative) const;

      /** Newton for disc @p d, @p q in place; throws if it fails. */
      void
      solve_disc(const unsigned int    d,
                 const double          beta,
                 std::vector<PinLoad> &pins,
                 support::DiscMotion  &q) const;

      const PairStiffnessModel     &model;
      const support::CrankSupports &supports;
      const double                  tolerance;
      const unsigned int            max_iterations;
      const double                  floor;
    };
  } // namespace analytic
} // namespace cycloid

#endif

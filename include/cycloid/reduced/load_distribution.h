#ifndef cycloid_reduced_load_distribution_h
#define cycloid_reduced_load_distribution_h

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <cycloid/reduced/local_contact.h>
#include <cycloid/support/crank_supports.h>

#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace cycloid
{
  namespace reduced
  {
    /** @brief One contact of the complementarity problem. */
    struct ContactPair
    {
      /** Moment arm about the disc centre [mm] (ContactPoint's contact). */
      double arm = 0;
      /** Initial clearance [mm]. */
      double clearance = 0;
      /**
       * Gap [mm] and arm [mm] of the pin against the disc turned rigidly
       * by beta [rad]. Empty: the linear c - beta l with the unloaded arm.
       * The exact one lets the contact point slide along the flank as the
       * disc turns: on a nearly conformal pair (pin in a concave flank)
       * the first touching point moves by tens of micrometres and its arm
       * by a few per cent (measured against the FE model, which resolves
       * it).
       */
      std::function<std::pair<double, double>(double)> rigid_gap;
      /** Length of the line contact the force acts on (2D: the tooth
       * width; 3D: the slice) [mm]. */
      double length = 1;
      /** Its near field. */
      LocalContact law{1., 1., 1.};
      /** The disc it is on. */
      unsigned int disc = 0;
      /** Unit normal from the disc towards the pin (a translation t of
       * the disc closes the gap by n . t). */
      dealii::Tensor<1, 2> normal;
    };

    /** @brief A solved load state of the reduced model. */
    struct ReducedSolution
    {
      /** Force of each contact [N] (>= 0). */
      std::vector<double> force;
      /** Rotation beta of the discs [rad]. */
      double rotation = 0;
      /** dT/dbeta at the solution [N mm/rad]. */
      double k_tangent = 0;
      /** Own compliance C(i,i) + h_i'(F_i) of each contact [mm/N]. */
      std::vector<double> compliance;
      /** Newton iterations over all active sets. */
      unsigned int iterations = 0;
      /** Active sets tried. */
      unsigned int active_sets = 0;
      /** Each disc's motion on its crank bearings (empty on rigid
       * supports). */
      std::vector<support::DiscMotion> motions;
      /** The elastic bodies' part F^T C F of the output work T beta
       * [N mm]. */
      double bodies_work = 0;
      /** The crank bearings' part of it [N mm]. */
      double bearings_work = 0;
    };

    /**
     * @brief The load distribution of the reduced model: find the forces
     * F_i >= 0 and the one rotation beta shared by every disc such that
     * each gap
     * @f[ g_i = c_i - \beta l_i + \sum_j C_{ij} F_j + h_i(F_i) \ge 0,
     *     \qquad F_i g_i = 0, \qquad \sum_i F_i l_i = T , @f]
     * where c_i - beta l_i is, more exactly, the gap of the rigidly turned
     * disc and l_i its arm (ContactPair::rigid_gap).
     * A primal-dual active set over the contacts (a contact with F_i < 0
     * leaves, one with g_i < 0 enters) with a Newton iteration on the
     * nonlinear h for each set; the set is exact, not a fixed-point guess.
     * A set seen twice (cycling) or the iteration limit is an error.
     */
    class ComplementaritySolver
    {
    public:
      /** @p compliance C [mm/N] (symmetric positive definite) of @p pairs. */
      ComplementaritySolver(const dealii::FullMatrix<double> &compliance,
                            const std::vector<ContactPair>   &pairs,
                            const double                      tolerance,
                            const unsigned int                max_iterations);

      /** Solve for torque @p torque [N mm], the first active set the
       * contacts that rotation @p beta_guess [rad] closes. */
      ReducedSolution
      solve(const double torque, const double beta_guess) const;

      /** Put the discs on crank bearings: each disc d then moves by
       * (t_d, theta_d) against them (support::CrankSupports), its pins'
       * gaps closing by n_i . t_d + (the rigid gap at theta_d), and the
       * Newton iteration of each active set also solves each disc's
       * equilibrium of force and moment. */
      void
      set_supports(const support::CrankSupports &supports);

    private:
      /** The primal-dual active set shared by both supports: from the
       * first active set (rotation @p beta_guess [rad]) with one force
       * per active contact, @p newton_on each set (forces in place,
       * returning its iterations), @p next_of the set after it, until a
       * set repeats itself (cycling is an error). @p F the forces, @p s's
       * iteration counts; returns the final set. @p floor [N]: the force
       * a contact entering the set starts from. */
      std::vector<unsigned int>
      active_set_loop(
        const double                                              torque,
        const double                                              beta_guess,
        const double                                              floor,
        const std::function<unsigned int(const std::vector<unsigned int> &,
                                         std::vector<double> &)> &newton_on,
        const std::function<
          std::vector<unsigned int>(const std::vector<unsigned int> &,
                                    const std::vector<double> &)> &next_of,
        std::vector<double>                                       &F,
        ReducedSolution                                           &s) const;

      /** The forces the first set @p active (rotation @p beta_guess
       * [rad]) starts from: T over the summed arms on each [N]. */
      std::vector<double>
      starting_forces(const std::vector<unsigned int> &active,
                      const double                     torque,
                      const double                     beta_guess) const;

      /** @p s's forces, own compliances and bodies' work from the solved
       * forces @p F. */
      void
      set_forces(const std::vector<double> &F,
                 const double               floor,
                 ReducedSolution           &s) const;

      /** The force below which the near field is linearised, 1e-9 of the
       * torque over the summed arms [N]. */
      double
      force_floor(const double torque) const;

      /** Each disc where its bearings alone carry the first active set's
       * starting forces (rotation @p beta_guess [rad]): the start of
       * solve_supported(). */
      std::vector<support::DiscMotion>
      initial_motions(const double torque,
                      const double beta_guess,
                      const double bearing_floor) const;

      /** solve() on crank bearings. */
      ReducedSolution
      solve_supported(const double torque, const double beta_guess) const;

      /** The residual of the problem on crank bearings for the active set
       * @p active (gaps, each disc's force and moment, the torque) and its
       * Jacobian in (F_active, (t_x, t_y, theta) per disc, beta). */
      void
      supported_system(const std::vector<unsigned int>        &active,
                       const std::vector<double>              &F,
                       const std::vector<support::DiscMotion> &q,
                       const double                            beta,
                       const double                            torque,
                       const double                            floor,
                       const double                            bearing_floor,
                       dealii::Vector<double>                 &r,
                       dealii::FullMatrix<double>             &J) const;

      /** Newton on crank bearings, like newton(). */
      unsigned int
      supported_newton(const std::vector<unsigned int>  &active,
                       const double                      torque,
                       const double                      floor,
                       const double                      bearing_floor,
                       std::vector<double>              &F,
                       std::vector<support::DiscMotion> &q,
                       double                           &beta) const;

      /** The set after @p active with forces @p F: the active contacts
       * that still push, and the open ones whose gap (@p rigid_gap_of(i),
       * the rigidly moved disc's, plus the bodies' give) the forces
       * close. */
      std::vector<unsigned int>
      next_set(const std::vector<unsigned int>           &active,
               const std::vector<double>                 &F,
               const std::function<double(unsigned int)> &rigid_gap_of) const;

      /** next_active_set() with the discs moved by @p q. */
      std::vector<unsigned int>
      next_supported_set(const std::vector<unsigned int>        &active,
                         const std::vector<double>              &F,
                         const std::vector<support::DiscMotion> &q) const;

      /** Gap and arm of contact @p i at rotation @p beta (rigid_gap or the
       * linear one). */
      std::pair<double, double>
      rigid_gap(const unsigned int i, const double beta) const;
      /** dl_i/dbeta [mm/rad] (0 for the linear gap). */
      double
      arm_slope(const unsigned int i, const double beta) const;
      /** Near-field approach h_i(F) [mm], extended linearly below the
       * force @p floor [N] (its slope is infinite at 0). */
      double
      approach(const unsigned int i,
               const double       force,
               const double       floor) const;
      /** dh_i/dF [mm/N], constant below @p floor. */
      double
      slope(const unsigned int i, const double force, const double floor) const;
      /** Newton on the active set @p active: forces @p F and rotation
       * @p beta updated in place; returns the iterations. */
      unsigned int
      newton(const std::vector<unsigned int> &active,
             const double                     torque,
             const double                     floor,
             std::vector<double>             &F,
             double                          &beta) const;

      /** The contacts closed by the rigid rotation @p beta_guess [rad]
       * under @p torque [N mm], or else the one with the smallest
       * clearance per arm on the loaded side. */
      std::vector<unsigned int>
      first_active_set(const double torque, const double beta_guess) const;

      /** The set after @p active with forces @p F [N] at rotation @p beta
       * [rad]: the active contacts that still push, and the open ones
       * whose gap the forces close. */
      std::vector<unsigned int>
      next_active_set(const std::vector<unsigned int> &active,
                      const std::vector<double>       &F,
                      const double                     beta) const;

      /** dT/dbeta [N mm/rad] on the final set @p active with forces @p F:
       * l^T (C + H')^-1 l with the gaps held closed, plus the turning of
       * the arms as the contact points slide. */
      double
      tangent_stiffness(const std::vector<unsigned int> &active,
                        const std::vector<double>       &F,
                        const double                     floor,
                        const double                     beta) const;

      const dealii::FullMatrix<double> C;
      const std::vector<ContactPair>   pairs;
      /** The crank bearings (none: rigid supports). */
      std::unique_ptr<support::CrankSupports> supports;
      const double                            tolerance;
      const unsigned int                      max_iterations;
    };
  } // namespace reduced
} // namespace cycloid

#endif

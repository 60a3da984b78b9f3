#ifndef cycloid_reduced_reduced_model_h
#define cycloid_reduced_reduced_model_h

#include <cycloid/analytic/stage_model.h>
#include <cycloid/reduced/coarse_model.h>
#include <cycloid/reduced/compliance.h>
#include <cycloid/reduced/load_distribution.h>
#include <cycloid/reduced/reduced_parameters.h>
#include <cycloid/results/stage_state.h>
#include <cycloid/stage/stage_scene.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace cycloid
{
  namespace reduced
  {
    /** A pin of a disc: (disc, pin). */
    using PinKey = std::pair<unsigned int, unsigned int>;
    /** A contact of the reduced model: (disc, pin, axial slice). */
    using ContactKey = std::array<unsigned int, 3>;

    template <int dim>
    class CompliancePath;

    /**
     * Gap [mm] and arm [mm] of contact @p c (at crank angle @p psi [rad])
     * as functions of the discs' rotation beta [rad], with the rigid
     * rotation linearised as in the FE model: the gap G(phi) and arm L(phi)
     * of the flank point at profile parameter phi are fitted by a
     * quadratic around the closest point, and the contact slides to the
     * point that closes first: gap = c - beta l - beta^2 L'^2/(2 G''),
     * arm = l + beta L'^2/G'' (doc/reduced-model.md §1).
     */
    std::function<std::pair<double, double>(double)>
    linearised_rigid_gap(const geometry::CycloidGeometry &geo,
                         const double                     psi,
                         const geometry::PinContact      &c);

    /** Whether contact @p c (crank angle @p psi) can carry a torque of
     * sign @p load_sign (+1, -1; 0: either): its arm, once the disc has
     * turned by 1e-3 rad, has that sign. */
    bool
    can_carry(const geometry::CycloidGeometry &geo,
              const double                     psi,
              const geometry::PinContact      &c,
              const int                        load_sign);

    /** The pins of @p model's stage that can_carry() a torque of sign
     * @p load_sign at crank angle @p psi [rad]. */
    std::set<PinKey>
    carrying_pins(const analytic::StageModel &model,
                  const double                psi,
                  const int                   load_sign);

    /**
     * @brief The reduced model of the stage at one crank angle: the
     * compliance of the scene's bodies (discs, pins, supports, housing)
     * condensed from a coarse FE model (CoarseModel, shared by the crank
     * angles of a run) onto the contacts of the loaded side, the near field
     * of each contact from the line-contact law (LocalContact), and the
     * load distribution as an exact complementarity problem
     * (ComplementaritySolver). Construction solves one load case per
     * contact on the coarse model (collective on its communicator); every
     * torque after that costs a small dense solve. Returns the same
     * analytic::LoadState and results::StageState as the analytical model, so
     * every report and run works with it.
     */
    template <int dim>
    class ReducedModel
    {
    public:
      /** Condense @p coarse (the scene of @p settings) at crank angle
       * @p psi [rad] onto the contacts of the side @p load_sign (+1, -1; 0
       * both); progress lines go to @p progress if given. */
      ReducedModel(const ReducedSettings &settings,
                   CoarseModel<dim>      &coarse,
                   const double           psi,
                   const int              load_sign,
                   std::ostream          *progress = nullptr);

      /** Condense @p coarse at @p psi onto the contacts of the pins
       * @p only, whatever side they are on (the anchors of a
       * CompliancePath). */
      ReducedModel(const ReducedSettings  &settings,
                   CoarseModel<dim>       &coarse,
                   const double            psi,
                   const std::set<PinKey> &only,
                   std::ostream           *progress = nullptr);

      /** The contacts of the side @p load_sign at @p psi, their compliance
       * interpolated from @p path (no solve). */
      ReducedModel(const ReducedSettings     &settings,
                   const CoarseModel<dim>    &coarse,
                   const double               psi,
                   const int                  load_sign,
                   const CompliancePath<dim> &path);

      /**
       * The stage of @p sample, the stage of @p nominal with other
       * manufacturing deviations (a tolerance study's sample), at
       * @p nominal's crank angle on the compliance @p nominal condensed: the
       * gaps, arms, contact points and near fields are the sample's own,
       * the compliance between two contacts the nominal stage's. A
       * deviation of a few um changes the gaps, not the bodies
       * (doc/tolerance.md measures what the reuse costs). The contacts are
       * @p nominal's pins: one the nominal stage could not load is left
       * out. No solve, no communication.
       */
      ReducedModel(const ReducedSettings &sample, const ReducedModel &nominal);

      /** The load state for output torque @p torque [N m], the first
       * active set from rotation @p beta_guess [rad] (0: the analytical
       * model's). */
      analytic::LoadState
      solve(const double torque, const double beta_guess) const;

      /** The zero-torque limit from side @p side (no force, so the same
       * as the analytical model's). */
      analytic::LoadState
      zero_torque_limit(const int side) const
      {
        return model.zero_torque_limit(pins, side, psi);
      }

      /** @p load as the stage state every model returns. */
      results::StageState
      stage_state(const analytic::LoadState &load) const;


      /** Contacts (load cases) condensed. */
      unsigned int
      n_contacts() const
      {
        return points.size();
      }

      /** The condensation's figures (asymmetry, iterations). */
      const Compliance &
      compliance() const
      {
        return condensed;
      }

      /** The contacts. */
      const std::vector<ContactPoint> &
      contacts() const
      {
        return points;
      }

      /** The key (disc, pin, slice) of each contact. */
      const std::vector<ContactKey> &
      contact_keys() const
      {
        return keys;
      }

    private:
      /** The contacts of the pins for which @p take holds (per disc, pin
       * and slice), their disc side placed where the coarse model has the
       * disc (its crank angle psi_mesh). */
      void
      select_contacts(
        const std::function<bool(const geometry::PinContact &)> &take);
      /** Gap and arm of contact @p c's pin against the disc turned
       * rigidly by beta (ContactPair::rigid_gap), from the exact profile. */
      std::function<std::pair<double, double>(double)>
      rigid_gap(const geometry::PinContact &c) const;
      /** The complementarity problem in the stage's units. */
      void
      build_solver();
      /** @p load's disc motions, bearing states and compliance breakdown
       * from the solution @p s at torque @p torque [N mm]. */
      void
      set_supported_figures(const ReducedSolution &s,
                            const double           torque,
                            analytic::LoadState   &load) const;

      const ReducedSettings settings;
      const double          psi;
      /** The crank angle the coarse model was meshed at [rad]. */
      const double                   psi_mesh;
      const analytic::StageModel     model;
      std::vector<analytic::PinLoad> pins;
      std::vector<ContactPoint>      points;
      /** Index into pins of each contact. */
      std::vector<unsigned int>              pin_of;
      std::vector<ContactKey>                keys;
      Compliance                             condensed;
      std::unique_ptr<ComplementaritySolver> solver;
      unsigned long                          n_dofs = 0;
    };

    /**
     * @brief The compliance of a crank sweep from a few anchor angles: the
     * coarse model condensed at each anchor onto every contact that can
     * carry the load anywhere in the sweep, and C(psi) between them by
     * Lagrange interpolation entry by entry. Over one mesh period a
     * contact moves about 0.5 mm along its flank (less than the probing
     * load's width) and C changes smoothly, while the load distribution,
     * the engaged pins and the gaps stay exact at every angle
     * (ReducedModel's third constructor). `Reduced/Anchor angles`.
     */
    template <int dim>
    class CompliancePath
    {
    public:
      /** Condense @p coarse at @p anchors [rad] onto the contacts that can
       * carry the side @p load_sign at any of @p angles [rad]. */
      CompliancePath(const ReducedSettings     &settings,
                     CoarseModel<dim>          &coarse,
                     const std::vector<double> &anchors,
                     const std::vector<double> &angles,
                     const int                  load_sign,
                     std::ostream              *progress);

      /** C [mm/N, 2D per N/mm] of the contacts @p keys at @p psi [rad]. */
      dealii::FullMatrix<double>
      at(const double psi, const std::vector<ContactKey> &keys) const;

    private:
      std::vector<double>                     anchors;
      std::map<ContactKey, unsigned int>      index;
      std::vector<dealii::FullMatrix<double>> matrices;
    };
  } // namespace reduced
} // namespace cycloid

#endif

#ifndef cycloid_analytic_stage_model_h
#define cycloid_analytic_stage_model_h

#include <cycloid/analytic/load_distribution.h>
#include <cycloid/analytic/pair_stiffness.h>
#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/parameters/material.h>
#include <cycloid/parameters/scene.h>
#include <cycloid/results/stage_state.h>

#include <memory>
#include <vector>

namespace cycloid
{
  namespace analytic
  {
    /**
     * @brief What the analytical model reads from the parameter file.
     */
    struct ModelSettings
    {
      geometry::GeometryParameters   geometry; ///< Subsection `Geometry`.
      parameters::MaterialParameters material; ///< Subsection `Material`.
      parameters::SceneParameters    scene;    ///< Subsection `Scene`.
      AnalyticParameters             analytic; ///< Subsection `Analytic`.
      support::CrankBearingParameters
        bearings; ///< Subsection `Crank bearings`.
    };

    /**
     * @brief The analytical model of the whole stage: exact clearances and
     * arms from the geometry, a pair-stiffness model chosen by name, and
     * the load distribution over the pins of one or two discs sharing one
     * rotation.
     */
    class StageModel
    {
    public:
      /** Builds the geometry (validating it) and the pair model. */
      explicit StageModel(const ModelSettings &settings);

      /** The geometry. */
      const geometry::CycloidGeometry &
      geometry() const
      {
        return geo;
      }

      /** The pair-stiffness model. */
      const PairStiffnessModel &
      pair_model() const
      {
        return *model;
      }

      /**
       * Unloaded pin geometry of every disc at crank angle @p psi [rad].
       * Throws if a clearance is negative (the scene cannot start from an
       * overlap).
       */
      std::vector<PinLoad>
      unloaded_pins(const double psi) const;

      /** Solve the load distribution at crank angle @p psi [rad] for
       * torque @p torque [N m], warm-started from @p beta_guess [rad]. */
      LoadState
      solve(const double psi,
            const double torque,
            const double beta_guess) const;

      /** Solve the load distribution over already computed unloaded pins
       * (see unloaded_pins()) at crank angle @p psi [rad], on the crank
       * bearings if there are any. */
      LoadState
      solve(const std::vector<PinLoad> &pins,
            const double                torque,
            const double                beta_guess,
            const double                psi) const
      {
        if (!prm.bearings.needle())
          return distribution.solve(pins, torque, beta_guess);
        return distribution.solve(pins, torque, beta_guess, supports(psi));
      }

      /** solve() on rigid supports whatever `Crank bearings` says: the
       * take-up and first active set of the reduced model when the
       * bearings have no clearance (the take-up is then the pins'). */
      LoadState
      solve_on_rigid_supports(const std::vector<PinLoad> &pins,
                              const double                torque,
                              const double                beta_guess) const
      {
        return distribution.solve(pins, torque, beta_guess);
      }

      /** The crank bearings at crank angle @p psi [rad] (Crank bearings =
       * needle). */
      support::CrankSupports
      supports(const double psi) const
      {
        return support::CrankSupports(prm.bearings,
                                      geo,
                                      prm.scene.n_discs,
                                      psi);
      }

      /** The zero-torque limit from side @p side (+1 or -1) over already
       * computed unloaded pins (LoadDistribution::zero_torque_limit()) at
       * crank angle @p psi [rad]. */
      LoadState
      zero_torque_limit(const std::vector<PinLoad> &pins,
                        const int                   side,
                        const double                psi) const
      {
        if (!prm.bearings.needle())
          return distribution.zero_torque_limit(pins, side);
        return distribution.zero_torque_limit(pins, side, supports(psi));
      }

      /**
       * The solved load state @p load at crank angle @p psi [rad] as the
       * stage state every model returns (cost figures other than the
       * iterations are the caller's).
       */
      results::StageState
      stage_state(const LoadState &load, const double psi) const;

      /** Distance from a disc-frame point to the load-introduction
       * surface (nearest crank hole, or the bore) [mm]. */
      double
      disc_depth(const dealii::Point<2> &p_disc) const;

    private:
      const ModelSettings                 prm;
      const geometry::CycloidGeometry     geo;
      std::unique_ptr<PairStiffnessModel> model;
      LoadDistribution                    distribution;
    };
  } // namespace analytic
} // namespace cycloid

#endif

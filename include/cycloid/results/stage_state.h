#ifndef cycloid_results_stage_state_h
#define cycloid_results_stage_state_h

#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace cycloid
{
  /**
   * The result every model of the stage returns (analytic, FE, and any
   * model added later), and the unit conversions between the models'
   * internal units and the reported ones. Nothing here knows how a state
   * was computed: postprocess::Report turns states into files and console
   * lines, so a new model gets every output by filling a StageState.
   */
  namespace results
  {
    /**
     * Unit conversions, in one place. Models compute in mm, N, N mm and
     * rad; the prm and the CSV files use N m, um, degrees and arcminutes.
     */
    namespace units
    {
      /** pi. */
      constexpr double pi = dealii::numbers::PI;
      /** Radians per degree. */
      constexpr double rad_per_deg = pi / 180.;
      /** Degrees per radian. */
      constexpr double deg_per_rad = 180. / pi;
      /** Radians per arcminute. */
      constexpr double rad_per_arcmin = pi / (180. * 60.);
      /** Arcminutes per radian. */
      constexpr double arcmin_per_rad = 180. * 60. / pi;
      /** Arcseconds per radian. */
      constexpr double arcsec_per_rad = 180. * 3600. / pi;
      /** N mm per N m (torques, and J per N mm inverted). */
      constexpr double Nmm_per_Nm = 1e3;
      /** N m per N mm (also J per N mm). */
      constexpr double Nm_per_Nmm = 1e-3;
      /** Micrometres per millimetre. */
      constexpr double um_per_mm = 1e3;
    } // namespace units

    /**
     * @brief One pin against one disc in a solved state, for the whole
     * tooth width. Forces in N, lengths in mm, angles in rad.
     */
    struct PinState
    {
      unsigned int disc = 0; ///< Disc index, from 0.
      unsigned int pin  = 0; ///< Pin index, from 0 (pin j at 360 deg j/zp).
      /** Force of the pin on the disc, housing frame: x component [N]. */
      double fx = 0;
      double fy = 0; ///< y component of the force [N].
      /** Its magnitude [N]. */
      double fn = 0;
      /** Signed moment arm about the disc centre; positive arms resist a
       * positive torque [mm]. */
      double arm = 0;
      /** Initial normal gap before load [mm]. */
      double clearance = 0;
      /** Tooth phase, 0 at the tooth root [rad]. */
      double phase = 0;
      /** Approach beta * arm - clearance (the models may clip it at 0)
       * [mm]. */
      double approach = 0;
      /** Pair stiffness dF/d approach (analytic models; 0 otherwise)
       * [N/mm]. */
      double pair_stiffness = 0;
      /** Unloaded contact point, housing frame [mm]. */
      dealii::Point<2> contact_point;
      /** Contact half-width of the model (FE: from the extent of the
       * active nodes; analytic: Hertz's) [mm]. */
      double contact_halfwidth = 0;
      /** Hertz line-contact half-width at this force [mm]. */
      double hertz_halfwidth = 0;
      /** Peak normal contact pressure of the model (FE: the largest nodal
       * pressure of the pair from the contact multipliers; analytic:
       * Hertz's) [MPa]. */
      double max_pressure = 0;
      /** Hertz peak pressure p0 = 2 F / (pi a b) at this force [MPa]. */
      double hertz_pressure = 0;
      /** Largest subsurface shear stress (Tresca) of the Hertz field at
       * this force [MPa]. */
      double max_shear_stress = 0;
      /** Its depth below the surface [mm]. */
      double max_shear_depth = 0;
      /** Active contact nodes of the pair (FE; 0 otherwise): the contact
       * zone's resolution. */
      unsigned int active_nodes = 0;
      /** Estimated error of fn, from the change against the next coarser
       * contact level (FE with an error estimate; NaN otherwise) [N]. */
      double fn_error = std::numeric_limits<double>::quiet_NaN();
      /** Contact nodes across the Hertz width: 2 hertz_halfwidth over the
       * slave nodes' spacing along the flank at the contact point (FE
       * states of a loaded pin; NaN otherwise). The pin forces' error
       * falls as its square (results::resolution_error()) [-]. */
      double hertz_nodes = std::numeric_limits<double>::quiet_NaN();
    };

    /**
     * @brief Relative error estimates of a state (FE with `Mesh/Error
     * estimate`; NaN where not estimated), e.g. 0.004 = 0.4 %.
     */
    struct ErrorEstimate
    {
      /** Of K_secant [-]. */
      double k_secant = std::numeric_limits<double>::quiet_NaN();
      /** Of K_tangent [-]. */
      double k_tangent = std::numeric_limits<double>::quiet_NaN();
      /** Of every pin force, relative to the largest pin force [-]. */
      double max_pin_force = std::numeric_limits<double>::quiet_NaN();
      /** The bulk mesh's part of the estimate (Mesh/Bulk error
       * estimate), the largest of its parts of the three figures above,
       * which include it; NaN where not estimated [-]. */
      double bulk = std::numeric_limits<double>::quiet_NaN();
      /** The model's own part of the estimate, where it has one that no
       * refinement removes (the reduced model's near-field law), relative,
       * included in the three figures above; NaN otherwise [-]. */
      double model = std::numeric_limits<double>::quiet_NaN();
      /** Contact refinement level of the state above the mesh's global
       * refinements (the finer of the two levels compared). */
      unsigned int contact_level = 0;
      /** Why a state that should have an estimate has none (the coarser
       * level failed); empty otherwise. */
      std::string failure;
      /** The levels compared, for the console, where they are not contact
       * levels (the reduced model's companion); empty for FE states. */
      std::string method;

      /** Whether the state has an estimate. */
      bool
      available() const
      {
        return !std::isnan(max_pin_force);
      }

      /** The largest of the three estimates (NaN estimates ignored). */
      double
      largest() const
      {
        double e = 0;
        for (const double x : {k_secant, k_tangent, max_pin_force})
          if (!std::isnan(x))
            e = std::max(e, x);
        return e;
      }
    };

    /**
     * @brief One crank bearing in a solved state (Crank bearings = needle).
     */
    struct BearingState
    {
      unsigned int disc  = 0; ///< Disc index, from 0.
      unsigned int crank = 0; ///< Crank hole, from 0 counter-clockwise.
      /** Force of the bearing on the disc, housing frame [N]. */
      double fx = 0;
      double fy = 0; ///< y component of the force [N].
      /** Radial deflection: the crank hole's centre against its
       * eccentric's, the clearance taken up included [mm]. */
      double deflection = 0;
      /** Rollers carrying load [-]. */
      unsigned int rollers_loaded = 0;
      /** Largest roller load [N]. */
      double max_roller_load = 0;
    };

    /**
     * @brief The output rotation of a state split by where it comes from
     * (doc/bearings.md): each part's share of the output work T beta
     * divided by T, so the parts sum to beta.
     */
    struct ComplianceBreakdown
    {
      /** The pin contacts: their clearances, near fields and the contact
       * points' slide (the rest of beta) [rad]. */
      double contacts = std::numeric_limits<double>::quiet_NaN();
      /** The elastic bodies (the reduced model's condensed compliance;
       * 0 for the analytical model, whose pair law holds them) [rad]. */
      double bodies = std::numeric_limits<double>::quiet_NaN();
      /** The crank bearings [rad]. */
      double bearings = std::numeric_limits<double>::quiet_NaN();
    };

    /**
     * @brief A solved load state of the stage: one crank angle, one load,
     * all discs (they share one rotation beta) and all pins, for the whole
     * tooth width, with what it cost.
     */
    struct StageState
    {
      /** Index of the state in the run (set by the run). */
      unsigned int step = 0;
      /** Crank angle [rad]. */
      double crank = 0;
      /** Output torque of the stage [N m]. */
      double torque = 0;
      /** Rotation beta of the discs from the kinematic position [rad]. */
      double rotation = 0;
      /** Tangent stiffness dT/dbeta [N m/rad] (NaN where not defined). */
      double k_tangent = 0;
      /** Rigid take-up rotation (lost motion before the first pin on the
       * loaded side touches) [rad]. */
      double takeup = 0;
      /** Reaction torque sum F * arm [N m]. */
      double reaction_torque = 0;
      /** Every pin of every disc, disc-major. */
      std::vector<PinState> pins;
      /** Every crank bearing of every disc (Crank bearings = needle),
       * disc-major. */
      std::vector<BearingState> bearings;
      /** Where the rotation comes from (models that can say). */
      ComplianceBreakdown breakdown;
      /** Its error estimate (FE states). */
      ErrorEstimate error;

      /** Active-set (FE) or torque-balance (analytic) iterations. */
      unsigned int iterations = 0;
      /** Preconditioner set-ups (AMG hierarchies or direct factorisations)
       * of the state, over its adaptive cycles (FE; 0 for analytic
       * states and zero-torque limits). */
      unsigned int preconditioner_setups = 0;
      /** Linear-solver iterations of the state. */
      unsigned long linear_iterations = 0;
      /** Active-set cycles that the FE state broke (its final solve; a
       * transient step's solves), and the largest tension that left at a
       * node over the largest nodal force (contact::ContactState). */
      unsigned int cycles_broken = 0;
      /** See cycles_broken [-]. */
      double cycle_tension = 0;
      /** Degrees of freedom (0 for models without a mesh). */
      unsigned long dofs = 0;
      /** Wall time of the state [s]. */
      double wall_s = 0;
      /** Peak resident memory of the run so far, summed over the ranks
       * [MB]. */
      double peak_memory_MB = 0;

      /** Secant stiffness T / beta [N m/rad]. */
      double
      k_secant() const
      {
        return rotation != 0 ? torque / rotation :
                               std::numeric_limits<double>::quiet_NaN();
      }

      /** Secant stiffness after the take-up, T / (beta - takeup)
       * [N m/rad]. */
      double
      k_secant_elastic() const
      {
        return rotation != takeup ? torque / (rotation - takeup) :
                                    std::numeric_limits<double>::quiet_NaN();
      }

      /** Pins carrying force, over all discs. */
      unsigned int
      pins_in_contact() const
      {
        return std::count_if(pins.begin(), pins.end(), [](const PinState &p) {
          return p.fn > 0;
        });
      }

      /** Largest pin force [N]. */
      double
      max_pin_force() const
      {
        double f = 0;
        for (const PinState &p : pins)
          f = std::max(f, p.fn);
        return f;
      }

      /** The pin with the highest peak contact pressure (the first of
       * equals; it need not be the most loaded pin: a pin nearer the tooth
       * tip meets a flank of smaller curvature radius); pins.end() if the
       * state has no pins. */
      std::vector<PinState>::const_iterator
      highest_pressure_pin() const
      {
        return pin_with_largest(&PinState::max_pressure);
      }

      /** The most loaded pin (the first of equals); pins.end() if the
       * state has no pins. */
      std::vector<PinState>::const_iterator
      most_loaded_pin() const
      {
        return pin_with_largest(&PinState::fn);
      }

      /** The pin with the largest @p field (the first of equals);
       * pins.end() if the state has no pins. */
      std::vector<PinState>::const_iterator
      pin_with_largest(double PinState::*field) const
      {
        return std::max_element(pins.begin(),
                                pins.end(),
                                [field](const PinState &a, const PinState &b) {
                                  return a.*field < b.*field;
                                });
      }
    };
  } // namespace results
} // namespace cycloid

#endif

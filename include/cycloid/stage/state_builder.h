#ifndef cycloid_stage_state_builder_h
#define cycloid_stage_state_builder_h

#include <deal.II/base/point.h>

#include <cycloid/contact/contact_problem.h>
#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/parameters/material.h>
#include <cycloid/parameters/scene.h>
#include <cycloid/results/stage_state.h>

#include <cmath>
#include <utility>
#include <vector>

namespace cycloid
{
  namespace stage
  {
    /**
     * The angle of @p x about @p centre in the xy plane, measured from the
     * direction @p from [rad], in [-pi, pi].
     */
    template <int dim>
    double
    angle_about(const dealii::Point<dim> &x,
                const dealii::Point<2>   &centre,
                const double              from)
    {
      return std::remainder(std::atan2(x[1] - centre[1], x[0] - centre[0]) -
                              from,
                            2. * results::units::pi);
    }

    /**
     * @brief What the state builder reads of the stage: its geometry and
     * material (Hertz widths and stresses), the scene (discs, plane
     * strain), and where the discs are.
     */
    struct StateBuilderSettings
    {
      const geometry::GeometryParameters   &geometry; ///< The stage.
      const parameters::MaterialParameters &material; ///< Hertz widths.
      const parameters::SceneParameters    &scene;    ///< Discs, pins.
      /** Crank angle of the discs' placement [rad]. */
      double psi;
      /** Crank angle the mesh was made at [rad]: a transient run's discs
       * have turned since, and the reactions are in the mesh axes. */
      double psi_mesh;
      /** Factor from the contact problem's forces to the whole stage: the
       * tooth width in 2D (forces per unit thickness), 1 in 3D. */
      double width_scale;
    };

    /**
     * @brief Turns a contact result of the FE model into the stage's
     * state: per disc and pin the force vector in the housing frame, its
     * arm, the clearance and contact point of the exact geometry, the
     * active contact's width and node resolution, the Hertz width and
     * stresses, and the peak nodal pressure.
     *
     * Why a class of its own: the pin-state extraction is the one place
     * where the FE solution meets the exact geometry of every pin and
     * disc; a per-pin or per-disc deviation of that geometry changes it
     * here and nowhere else in the stage. It holds references only, so a
     * StageScene makes one for each state (the placement changes between
     * states of a transient run).
     */
    template <int dim>
    class StateBuilder
    {
    public:
      /** A builder over the contact problem @p contact, whose slave nodes
       * belong to the stage of @p geo as @p settings place it. */
      StateBuilder(const StateBuilderSettings         &settings,
                   const geometry::CycloidGeometry    &geo,
                   const contact::ContactProblem<dim> &contact);

      /**
       * The stage's state for @p result of the contact problem, solved for
       * the torque @p torque [N m] (for the whole tooth width): pin forces
       * in the housing frame, arms, clearances, contact widths, beta,
       * tangent and take-up. The cost figures other than iterations and
       * DoFs are the caller's to fill.
       */
      results::StageState
      state(const contact::ContactState &result, const double torque) const;

      /**
       * The limit of the state as the torque goes to zero from side
       * @p side (+1 or -1): the discs turned by the rigid take-up towards
       * that side, no pin force (see StageScene::zero_torque_limit()).
       */
      results::StageState
      zero_torque_limit(const int side) const;

      /** The rigid take-up rotation towards the side @p sign of the exact
       * geometry at the placement [rad] (unsigned). Throws if no pin can
       * carry a torque of that sign. */
      double
      takeup_rotation(const int sign) const;

      /** Spacing of the slave nodes of disc @p d along the flank at its
       * unloaded contact point @p contact_point with pin @p j: the smaller
       * gap between the node nearest the point and its neighbours, as an
       * arc on the pin [mm]; 0 if the pair has fewer than two nodes. */
      double
      flank_node_spacing(const unsigned int      d,
                         const unsigned int      j,
                         const dealii::Point<2> &contact_point) const;

    private:
      /** A state with one PinState per disc and pin, numbered. */
      results::StageState
      empty_state() const;
      /** Per disc and pin: force sums in the housing frame and arm. */
      void
      sum_pin_forces(std::vector<results::PinState> &pins) const;
      /** Per pin of @p s: arm (of unloaded pins), clearance, phase,
       * contact point, approach, contact and Hertz widths, Hertz stresses;
       * adds the pins' moments to the reaction torque. */
      void
      set_pin_geometry(results::StageState &s) const;
      /** Per disc and pin: the largest nodal contact pressure [MPa]. */
      void
      set_peak_pressures(std::vector<results::PinState> &pins) const;
      /** Half-width of the active contact of disc @p d on pin @p j [mm]. */
      double
      contact_halfwidth(const unsigned int      d,
                        const unsigned int      j,
                        const dealii::Point<2> &contact_point) const;
      /** Angle about pin @p j's centre of each slave node of disc @p d
       * that faces it, from the unloaded contact point @p contact_point
       * (in [-pi, pi]), with the active set's flag; in 3D one entry per
       * node, so an angle repeats once per axial node. */
      std::vector<std::pair<double, bool>>
      pair_node_angles(const unsigned int      d,
                       const unsigned int      j,
                       const dealii::Point<2> &contact_point) const;

      const StateBuilderSettings          settings;
      const geometry::CycloidGeometry    &geo;
      const contact::ContactProblem<dim> &contact;
    };
  } // namespace stage
} // namespace cycloid

#endif

#ifndef cycloid_parameters_scene_h
#define cycloid_parameters_scene_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace cycloid
{
  namespace parameters
  {
    /**
     * @brief The scene: how much of the stage is modelled and how
     * (subsection `Scene`). "Model no more than a scene needs": the
     * analytical model uses Number of discs, Pins and Load introduction;
     * the FE scenes use all entries. `Number of discs = auto` (the default)
     * is resolved by resolve_number_of_discs(), where the run mode is
     * known.
     */
    struct SceneParameters
    {
      /** Pin model. */
      enum class PinModel
      {
        elastic,
        rigid
      };
      /** What holds the pins. */
      enum class PinSupport
      {
        axis,
        housing
      };
      /** Which disc surfaces turn rigidly by the load rotation beta. */
      enum class LoadIntroduction
      {
        bore,
        crank_holes
      };

      /** Spatial dimension of an FE scene (2: plane strain, 3). */
      unsigned int dimension = 2;
      /** Number of cycloid discs (1 or 2; an RV stage has 2, half a turn
       * apart). */
      unsigned int n_discs = 2;
      /** Whether the file leaves Number of discs at `auto` (then n_discs
       * is 2 until resolve_number_of_discs()). */
      bool n_discs_auto = false;
      /** Elastic or rigid pins. */
      PinModel pins = PinModel::elastic;
      /** Pin support. */
      PinSupport pin_support = PinSupport::axis;
      /** Radius of the rigid core held fixed around each pin axis [mm]. */
      double pin_core_radius = 0.5;
      /** Load introduction surfaces. */
      LoadIntroduction load_introduction = LoadIntroduction::crank_holes;

      /** Declare subsection `Scene`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsection `Scene`. */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /**
       * Resolve `Number of discs = auto` for a run that is an FE run
       * (@p fe_run: mesh, quasi-static, phase-sweep, transient) or not:
       * a 2D FE scene models one disc (plane strain has no second disc
       * beside the first), every other run the stage's two. Returns the
       * note the run prints ("2D FE: one disc (Scene/Number of discs =
       * auto)"), or "" if nothing was resolved to other than 2.
       */
      std::string
      resolve_number_of_discs(const bool fe_run);
    };
  } // namespace parameters
} // namespace cycloid

#endif

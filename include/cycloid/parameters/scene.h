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
     * the FE scenes use all entries.
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
    };
  } // namespace parameters
} // namespace cycloid

#endif

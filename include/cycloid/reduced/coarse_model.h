#ifndef cycloid_reduced_coarse_model_h
#define cycloid_reduced_coarse_model_h

#include <deal.II/base/timer.h>

#include <cycloid/reduced/compliance.h>
#include <cycloid/reduced/reduced_parameters.h>
#include <cycloid/stage/stage_scene.h>

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace cycloid
{
  namespace reduced
  {
    /** @brief What the reduced model reads: the FE scene (its coarse
     * model) and subsection `Reduced`. */
    struct ReducedSettings
    {
      stage::StageSettings stage;   ///< The scene, mesh and materials.
      ReducedParameters    reduced; ///< Subsection `Reduced`.

      /** The half-width w of the probing load [mm] (resolving `auto`). */
      double
      load_half_width() const;

      /**
       * The companion of the error estimate: the same scene one level
       * coarser. One contact refinement fewer where the coarse model has
       * any, else the in-plane element sizes (contact, flank, pin, far
       * field) doubled; an `auto` load half-width follows the mesh (an
       * explicit one is doubled), and 3D keeps half the axial slices (at
       * least one). Its own estimate is off.
       */
      ReducedSettings
      coarser() const;

      /** What coarser() changes, for the console. */
      std::string
      coarser_description() const;
    };

    /**
     * @brief The coarse FE model of the scene that the reduced model
     * condenses: meshed once at crank angle psi with its fine zones along
     * the contact paths of psi ... psi + sweep, assembled once without
     * contact, factorised at the first condensation and kept. Every crank
     * angle of a sweep condenses on it: the discs at another crank angle are
     * a rigid motion away from their meshes and the pins and housing do not
     * move, and the bodies are separate linear systems (joined only at the
     * contacts, which the condensation leaves open), so their compliance
     * between two material points does not change; only the contact points
     * move along the flanks and around the pins.
     */
    template <int dim>
    class CoarseModel
    {
    public:
      /** Mesh and assemble (collective on @p comm); refined at the pins of
       * the side @p load_sign (+1, -1; 0 both). */
      CoarseModel(const ReducedSettings &settings,
                  const double           psi,
                  const double           sweep,
                  const int              load_sign,
                  const MPI_Comm         comm);

      /** Crank angle of the mesh [rad]. */
      double
      crank_angle() const
      {
        return psi_mesh;
      }

      /** The compliance at @p points (condense_compliance()); the first
       * call factorises. */
      Compliance
      condense(const std::vector<ContactPoint> &points, std::ostream *progress);

      /** DoFs of the coarse model. */
      unsigned long
      dofs() const
      {
        return n_dofs;
      }

      /** Wall time of each stage so far [s]: the scene's ("make grid",
       * "setup system", ...) and the condensation's ("reduced: assembly",
       * "reduced: load vectors", "reduced: solves"), on rank 0. */
      std::map<std::string, double>
      stage_times();

    private:
      const ReducedSettings  settings;
      const double           psi_mesh;
      dealii::TimerOutput    timing;
      stage::StageScene<dim> scene;
      unsigned long          n_dofs;
    };
  } // namespace reduced
} // namespace cycloid

#endif

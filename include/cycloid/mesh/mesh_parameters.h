#ifndef cycloid_mesh_mesh_parameters_h
#define cycloid_mesh_mesh_parameters_h

#include <deal.II/base/parameter_handler.h>

namespace cycloid
{
  namespace mesh
  {
    /**
     * @brief How an FE state estimates its own error and what it does
     * with it (entries of subsection `Mesh`; results/error_estimate.h
     * computes it, doc/error-estimate.md validates it).
     *
     * The state is solved on three nested contact levels: the mesh asked
     * for (level L) and the same mesh with its finest cells, which all lie
     * at the contacts, coarsened once (L-1) and twice (L-2). A quantity's
     * estimate is the larger of its change from L-1 to L and half its
     * change from L-2 to L-1: the error is taken to fall at least by half
     * per level, so a change that fell by more than that is not trusted
     * until a further level confirms it (two levels alone can agree by
     * chance, measured on the seed case).
     */
    struct ErrorControl
    {
      /** `Mesh/Error estimate`: auto (2D on, 3D off unless a target
       * accuracy is set), true or false. */
      enum class Mode
      {
        automatic,
        on,
        off
      };
      /** Whether to estimate. */
      Mode mode = Mode::automatic;
      /** States whose largest estimate exceeds this are flagged [-]. */
      double warning_threshold = 0.02;
      /** Refine at the active contacts until the largest estimate is
       * below this (0: off) [-]. */
      double target_accuracy = 0;
      /** Whether `Target accuracy = auto`: AllParameters resolves it to
       * warning_threshold for 2D quasi-static runs and phase sweeps (the
       * mesh the user gets then is one the warning would not flag), to 0
       * otherwise. A sweep under an automatic target does not repeat
       * itself finer (each repeat refines every phase, minutes in 2D). */
      bool automatic_target = false;
      /** `Mesh/Bulk error estimate`: add to the estimate of every state
       * that has one the error of the bulk mesh, from the state solved
       * once more with every cell below the two finest levels refined
       * once (StageScene::solve_bulk_level()). The contact levels all
       * share those cells, so their differences do not contain their
       * error: in 2D 0.06-0.43 % of K_secant and up to 1.2 % of K_tangent
       * at the default element sizes, more than the contact levels'
       * estimate of a resolved mesh (doc/error-estimate.md, "The bulk
       * mesh"). */
      bool bulk = false;
      /** Whether `Bulk error estimate = auto`: AllParameters resolves it
       * to on for 2D states with an estimate and to off in 3D (there the
       * bulk solve has several times the state's DoFs). */
      bool automatic_bulk = true;
      /** Refinement cycles the target may add per state [-]. */
      unsigned int max_cycles = 4;
      /** Phase sweeps under a target: repeats, each one contact level
       * beyond the finest phase of the pass before, while the
       * fluctuation is not resolved [-]. */
      unsigned int max_sweep_refinements = 2;
      /** Contact levels below the mesh asked for that the estimate
       * solves. */
      static constexpr unsigned int coarser_levels = 2;

      /** Whether FE states of a @p dim-dimensional scene estimate their
       * error. */
      bool
      estimates(const unsigned int dim) const
      {
        return mode == Mode::on ||
               (mode == Mode::automatic && (dim == 2 || target_accuracy > 0));
      }

      /** Whether FE states of a @p dim-dimensional scene also solve the
       * bulk level (resolved: AllParameters sets bulk for auto). */
      bool
      bulk_level(const unsigned int dim) const
      {
        return estimates(dim) && bulk;
      }
    };

    /**
     * @brief Subsection `Mesh`: element sizes of the gmsh mesh, the axial
     * layering of 3D scenes and a-priori refinement in deal.II.
     *
     * The size field is graded from the contact points (the closest points
     * between every pin and every disc at the scene's crank angle):
     * h(x) = min(h_coarse, h_contact + g * max(0, d(x) - r_fine)), with d
     * the distance to the nearest contact point; additionally h <= h_flank
     * in the toothed ring of the discs and h <= h_pin in the pins, so that
     * the coarse mesh follows the curved boundaries.
     */
    struct MeshParameters
    {
      /** Element size at the contact points [mm]. */
      double contact_size = 0.25;
      /** Radius around each contact point meshed with contact_size [mm]. */
      double fine_radius = 0.3;
      /** Growth of the element size with the distance from a contact
       * point [mm/mm]. */
      double grading = 0.25;
      /** Largest element size along the tooth flanks [mm]. */
      double flank_size = 1.0;
      /** Largest element size in the pins [mm]. */
      double pin_size = 1.0;
      /** Largest element size anywhere (disc interior, housing) [mm]. */
      double coarse_size = 6.0;
      /** Number of element layers through the width of one disc (3D). */
      unsigned int axial_layers = 3;
      /** Number of element layers through the axial gap between the discs
       * (3D, pins and housing only). */
      unsigned int gap_layers = 1;
      /** Global refinements after reading the mesh. */
      unsigned int global_refinements = 0;
      /** A-priori refinements of the cells near the contact points. */
      unsigned int contact_refinements = 0;
      /** Radius around the contact points refined a priori [mm]. */
      double contact_refinement_radius = 0.5;
      /** Refine a priori only at the contacts on the loaded side (the pins
       * whose moment arm resists the load), not at every pin. */
      bool refine_loaded_side_only = false;
      /** Polynomial degree of the FE displacement (1 or 2). */
      unsigned int degree = 1;
      /** Adaptive refinement cycles at the active contact nodes. */
      unsigned int adaptive_cycles = 0;
      /** The error estimate of FE states and what follows from it. */
      ErrorControl error;
      /** Mesh psi mod the mesh period and turn by whole pin pitches. */
      bool periodic = true;
      /** Write the gmsh mesh (with physical groups) as stage.msh. */
      bool write_msh = false;
      /** Hold the mesh on p4est (each refined cell on one rank) rather than
       * on every rank. */
      bool distributed = false;

      /** Declare subsection `Mesh`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsection `Mesh`. */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace mesh
} // namespace cycloid

#endif

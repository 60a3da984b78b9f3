#ifndef cycloid_reduced_reduced_parameters_h
#define cycloid_reduced_reduced_parameters_h

#include <deal.II/base/parameter_handler.h>

namespace cycloid
{
  /**
   * The reduced model of the stage (`Run = reduced`): the compliance of
   * every body condensed from a coarse FE model onto the contact points,
   * the near field of each contact from the analytic line-contact law,
   * and the load distribution as a complementarity problem over the pins
   * (doc/reduced-model.md).
   */
  namespace reduced
  {
    /**
     * @brief Subsection `Reduced`: the coarse FE model that gives the
     * compliance, and the load that probes it.
     */
    struct ReducedParameters
    {
      /** Marks an `auto` entry. */
      static constexpr int automatic = -1;
      /** A-priori refinements of the coarse model at the loaded pins
       * (replaces Mesh/Contact refinements in a reduced run) [-];
       * automatic: 2 in 2D, 0 in 3D. */
      int contact_refinements = automatic;
      /** Half-width w of the semi-elliptic pressure that loads the coarse
       * model at each contact [mm]; 0: auto, 4 elements at the contact. */
      double load_half_width = 0;
      /** 3D: element layers through each disc's width in the coarse model
       * (replaces Mesh/Axial layers per disc) [-]. */
      unsigned int axial_layers = 1;
      /** 3D: slices of each disc's width, one contact force each [-]. */
      unsigned int axial_slices = 2;
      /** Crank angles at which a sweep of more crank angles condenses the
       * coarse model, the others interpolated (0: condense at every
       * crank angle) [-]. */
      unsigned int anchor_angles = 3;
      /** Estimate each state's error from the same state on a coarser
       * companion model (ReducedSettings::coarser()). */
      bool error_estimate = true;

      /** The contact refinements of a scene of dimension @p dim. */
      unsigned int
      refinements(const unsigned int dim) const
      {
        return contact_refinements == automatic ? (dim == 2 ? 2 : 0) :
                                                  contact_refinements;
      }

      /** Declare subsection `Reduced`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsection `Reduced`. */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace reduced
} // namespace cycloid

#endif

#ifndef cycloid_parameters_material_h
#define cycloid_parameters_material_h

#include <deal.II/base/parameter_handler.h>

namespace cycloid
{
  namespace parameters
  {
    /**
     * @brief Isotropic linear-elastic material of one body.
     */
    struct ElasticMaterial
    {
      /** Young's modulus [MPa]. */
      double youngs_modulus;
      /** Poisson's ratio [-], in (-1, 0.5). */
      double poissons_ratio;
      /** Density [kg/m^3]. */
      double density;

      /** Plane-strain modulus E / (1 - nu^2) [MPa]. */
      double
      plane_strain_modulus() const
      {
        return youngs_modulus / (1. - poissons_ratio * poissons_ratio);
      }
    };

    /**
     * @brief Materials of the disc, the pins and the housing (subsection
     * `Material`). Defaults: 20CrMnTi discs and pins (E = 212000 MPa,
     * nu = 0.3), QT450 housing (E = 173000 MPa, nu = 0.3) as in the seed's
     * Table 2.
     */
    struct MaterialParameters
    {
      /** Cycloid discs. */
      ElasticMaterial disc{212000., 0.3, 7850.};
      /** Pins. */
      ElasticMaterial pin{212000., 0.3, 7850.};
      /** Pin housing. */
      ElasticMaterial housing{173000., 0.3, 7100.};
      /** Peak contact pressure above which a run warns [MPa] (0: never):
       * the contact fatigue limit of case-hardened steel. */
      double allowable_contact_pressure = 1500.;

      /** Declare subsection `Material`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsection `Material`; throws naming the entry on a modulus
       * <= 0 or a Poisson's ratio outside (-1, 0.5). */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace parameters
} // namespace cycloid

#endif

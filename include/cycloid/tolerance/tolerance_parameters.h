#ifndef cycloid_tolerance_tolerance_parameters_h
#define cycloid_tolerance_tolerance_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace cycloid
{
  /**
   * Tolerance studies (`Run = tolerance`): random manufacturing deviations
   * drawn from the tolerance bands of a drawing, every sample solved with
   * the reduced (or analytical) model on the nominal stage's compliance,
   * and the distributions of the stage's figures (doc/tolerance.md).
   */
  namespace tolerance
  {
    /**
     * @brief Subsection `Tolerance study`: which model solves the samples,
     * how many, from which random seed, and the tolerance bands they are
     * drawn from.
     */
    struct ToleranceParameters
    {
      /** The model that solves every sample. */
      enum class Model
      {
        reduced,
        analytic
      };
      /** How a deviation is spread over its band. */
      enum class Distribution
      {
        /** Normal, the band being +-3 sigma (a capable process). */
        normal,
        /** Uniform over the band (the worst case a gauge lets through). */
        uniform
      };

      /** The model of the samples. */
      Model model = Model::reduced;
      /** Samples drawn beyond the nominal stage [-]. */
      unsigned int n_samples = 1000;
      /** Seed of the random draws; sample s is drawn from (seed, s) alone,
       * so the samples do not depend on the number of ranks [-]. */
      unsigned int seed = 1;
      /** The distribution of every deviation in its band. */
      Distribution distribution = Distribution::normal;
      /** Diameter of the true-position circle of each pin centre [um]. */
      double pin_position = 0;
      /** +- band of each pin's radius [um]. */
      double pin_radius = 0;
      /** +- band of each disc's eccentricity [um]. */
      double eccentricity = 0;
      /** +- band of each disc's angular placement [arcmin]. */
      double disc_angle = 0;
      /** +- band of each disc's Delta rp and Delta rrp, each [um]. */
      double profile = 0;
      /** Also draw the study once per band with that band alone, for each
       * band's share of the variance (`tolerance_sensitivity.csv`). */
      bool sensitivity = true;

      /** Whether any band is wider than zero. */
      bool
      any() const
      {
        return pin_position > 0 || pin_radius > 0 || eccentricity > 0 ||
               disc_angle > 0 || profile > 0;
      }

      /** The model's name as in the parameter file. */
      std::string
      model_name() const
      {
        return model == Model::reduced ? "reduced" : "analytic";
      }

      /** Declare subsection `Tolerance study`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsection `Tolerance study`. */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace tolerance
} // namespace cycloid

#endif

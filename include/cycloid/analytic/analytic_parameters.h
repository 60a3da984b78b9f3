#ifndef cycloid_analytic_analytic_parameters_h
#define cycloid_analytic_analytic_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace cycloid
{
  namespace analytic
  {
    /**
     * @brief Subsection `Analytic`: which pair-stiffness model the
     * analytical load-distribution model uses, and its constants.
     */
    struct AnalyticParameters
    {
      /** Name of the pair-stiffness model: "seed" or "line-contact". */
      std::string pair_model = "line-contact";
      /** The seed's coefficient lambda (manufacturing errors) [-]. */
      double load_sharing_coefficient = 0.7;
      /** Relative tolerance of the torque balance of the load
       * distribution [-]. */
      double tolerance = 1e-12;
      /** Iteration limit of the load-distribution solve. */
      unsigned int max_iterations = 200;

      /** Declare subsection `Analytic`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsection `Analytic`. */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace analytic
} // namespace cycloid

#endif

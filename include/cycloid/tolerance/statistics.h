#ifndef cycloid_tolerance_statistics_h
#define cycloid_tolerance_statistics_h

#include <vector>

namespace cycloid
{
  namespace tolerance
  {
    /**
     * @brief The distribution of one figure over a study's samples, as a
     * row of `tolerance_summary.csv` gives it.
     */
    struct Summary
    {
      double nominal = 0; ///< The nominal stage's value (sample 0).
      double mean    = 0; ///< Mean over the samples.
      double std     = 0; ///< Standard deviation (n - 1 in the divisor).
      double p05     = 0; ///< 5th percentile.
      double p50     = 0; ///< Median.
      double p95     = 0; ///< 95th percentile.
      double min     = 0; ///< Smallest value.
      double max     = 0; ///< Largest value.
      /** Monte-Carlo standard error of the mean, std / sqrt(n). */
      double standard_error = 0;
      /** Samples the figures are taken over. */
      unsigned int n = 0;
    };

    /**
     * Percentile @p q (0 to 1) of the sorted @p values by linear
     * interpolation between the order statistics at q (n - 1) (the
     * definition numpy.percentile uses by default, so a plot script
     * recomputes the same numbers). NaN if @p values is empty.
     */
    double
    percentile(const std::vector<double> &sorted, const double q);

    /** The summary of @p values (NaNs left out) around @p nominal. */
    Summary
    summarise(const double nominal, std::vector<double> values);
  } // namespace tolerance
} // namespace cycloid

#endif

#include <cycloid/tolerance/statistics.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cycloid
{
  namespace tolerance
  {
    double
    percentile(const std::vector<double> &sorted, const double q)
    {
      if (sorted.empty())
        return std::numeric_limits<double>::quiet_NaN();
      const double       at = q * (sorted.size() - 1);
      const unsigned int lo = static_cast<unsigned int>(std::floor(at));
      const unsigned int hi = std::min<unsigned int>(lo + 1, sorted.size() - 1);
      return sorted[lo] + (at - lo) * (sorted[hi] - sorted[lo]);
    }



    Summary
    summarise(const double nominal, std::vector<double> values)
    {
      values.erase(std::remove_if(values.begin(),
                                  values.end(),
                                  [](const double x) { return std::isnan(x); }),
                   values.end());
      std::sort(values.begin(), values.end());
      Summary s;
      s.nominal = nominal;
      s.n       = values.size();
      if (values.empty())
        {
          const double nan = std::numeric_limits<double>::quiet_NaN();
          s.mean = s.std = s.p05 = s.p50 = s.p95 = s.min = s.max =
            s.standard_error                             = nan;
          return s;
        }
      double sum = 0;
      for (const double x : values)
        sum += x;
      s.mean    = sum / values.size();
      double ss = 0;
      for (const double x : values)
        ss += (x - s.mean) * (x - s.mean);
      s.std = values.size() > 1 ? std::sqrt(ss / (values.size() - 1)) : 0.;
      s.standard_error = s.std / std::sqrt(double(values.size()));
      s.p05            = percentile(values, 0.05);
      s.p50            = percentile(values, 0.50);
      s.p95            = percentile(values, 0.95);
      s.min            = values.front();
      s.max            = values.back();
      return s;
    }
  } // namespace tolerance
} // namespace cycloid

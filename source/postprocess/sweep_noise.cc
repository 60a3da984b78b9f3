#include <deal.II/base/exceptions.h>

#include <cycloid/postprocess/sweep_noise.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cycloid
{
  namespace postprocess
  {
    SweepNoise
    sweep_noise(const std::vector<double> &x,
                const std::vector<double> &coarser)
    {
      AssertThrow(x.size() >= 2, dealii::ExcInternalError());
      const double nan  = std::numeric_limits<double>::quiet_NaN();
      double       mean = 0;
      for (const double v : x)
        mean += v;
      mean /= x.size();
      const auto [lo, hi] = std::minmax_element(x.begin(), x.end());

      SweepNoise n;
      n.fluctuation = (*hi - *lo) / mean;
      n.closure     = std::abs(x.back() / x.front() - 1);
      n.roughness   = nan;
      if (x.size() >= 5)
        {
          double sum = 0;
          for (unsigned int i = 1; i + 1 < x.size(); ++i)
            sum += std::pow(x[i + 1] - 2 * x[i] + x[i - 1], 2);
          const double sigma = std::sqrt(sum / (x.size() - 2) / 6.);
          n.roughness        = 3 * sigma / std::abs(mean);
        }
      n.refinement = nan;
      if (coarser.size() == x.size())
        {
          double shift = 0;
          for (unsigned int i = 0; i < x.size(); ++i)
            shift += (x[i] - coarser[i]) / x.size();
          n.refinement = 0;
          for (unsigned int i = 0; i < x.size(); ++i)
            n.refinement =
              std::max(n.refinement,
                       std::abs(x[i] - coarser[i] - shift) / std::abs(mean));
          n.floor = std::max(n.closure, n.refinement);
        }
      else if (std::isnan(n.roughness))
        n.floor = n.closure > 1e-9 ? n.closure : nan;
      else
        n.floor = std::max(n.closure, n.roughness);
      n.resolved = !std::isnan(n.floor) && n.fluctuation > 2 * n.floor;
      return n;
    }
  } // namespace postprocess
} // namespace cycloid

#include <cycloid/mesh/mesh_request.h>

#include <algorithm>

namespace cycloid
{
  namespace mesh
  {
    int
    common_sign(const std::vector<double> &loads)
    {
      const bool positive = std::all_of(loads.begin(),
                                        loads.end(),
                                        [](const double v) { return v >= 0.; });
      const bool negative = std::all_of(loads.begin(),
                                        loads.end(),
                                        [](const double v) { return v <= 0.; });
      return positive == negative ? 0 : (positive ? 1 : -1);
    }
  } // namespace mesh
} // namespace cycloid

#include <cycloid/mesh/quad_split.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace cycloid
{
  namespace mesh
  {
    namespace internal
    {
      std::vector<std::vector<unsigned int>>
      split_into_quadrilaterals(
        const std::vector<std::vector<unsigned int>>          &elements,
        std::vector<double>                                   &coordinates,
        const std::vector<Circle>                             &circles,
        const std::set<std::pair<unsigned int, unsigned int>> &on_circle)
      {
        const auto point = [&](const unsigned int v) {
          return dealii::Point<2>(coordinates[3 * v], coordinates[3 * v + 1]);
        };
        const auto add = [&](const dealii::Point<2> &p) {
          coordinates.push_back(p[0]);
          coordinates.push_back(p[1]);
          coordinates.push_back(0.);
          return static_cast<unsigned int>(coordinates.size() / 3 - 1);
        };
        std::map<std::pair<unsigned int, unsigned int>, unsigned int> middle;
        const auto midpoint = [&](const unsigned int a, const unsigned int b) {
          const auto key = std::minmax(a, b);
          auto       it  = middle.find(key);
          if (it != middle.end())
            return it->second;
          const dealii::Point<2> pa = point(a), pb = point(b);
          dealii::Point<2>       m = 0.5 * (pa + pb);
          if (on_circle.count(key))
            for (const Circle &c : circles)
              if (std::abs(pa.distance(c.centre) - c.radius) < 1e-8 &&
                  std::abs(pb.distance(c.centre) - c.radius) < 1e-8)
                {
                  m = c.centre +
                      (m - c.centre) * (c.radius / m.distance(c.centre));
                  break;
                }
          return middle[key] = add(m);
        };
        std::vector<std::vector<unsigned int>> result;
        for (const auto &el : elements)
          {
            const unsigned int n = el.size();
            dealii::Point<2>   centroid;
            for (const unsigned int v : el)
              centroid += point(v) / n;
            const unsigned int c = add(centroid);
            for (unsigned int k = 0; k < n; ++k)
              {
                const unsigned int prev = el[(k + n - 1) % n],
                                   next = el[(k + 1) % n];
                result.push_back(
                  {el[k], midpoint(el[k], next), c, midpoint(prev, el[k])});
              }
          }
        return result;
      }
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid

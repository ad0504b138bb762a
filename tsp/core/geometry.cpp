#include "tsp/core/geometry.h"

#include <algorithm>

namespace tsp {

Aabb geometric_box(const Box& box, const Dims& d) {
  Aabb g;
  for (int a = 0; a < 3; ++a) {
    g.lo[a] = box.lo[a];
    g.hi[a] = std::min(box.hi[a], d[a] - 1);
  }
  return g;
}

}  // namespace tsp

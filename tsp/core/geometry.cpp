#include "tsp/core/geometry.h"

#include <algorithm>
#include <cmath>

#include "tsp/core/number_text.h"

namespace tsp {

namespace {
constexpr double kHuge = 1e300;
}  // namespace

Aabb empty_aabb() { return Aabb{{kHuge, kHuge, kHuge}, {-kHuge, -kHuge, -kHuge}}; }

bool is_empty(const Aabb& b) { return b.lo[0] > b.hi[0] || b.lo[1] > b.hi[1] || b.lo[2] > b.hi[2]; }

void grow(Aabb& box, const std::array<double, 3>& p) {
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = std::min(box.lo[a], p[a]);
    box.hi[a] = std::max(box.hi[a], p[a]);
  }
}

void unite(Aabb& box, const Aabb& other) {
  if (is_empty(other)) return;
  grow(box, other.lo);
  grow(box, other.hi);
}

Aabb intersection(const Aabb& a, const Aabb& b) {
  Aabb r;
  for (int k = 0; k < 3; ++k) {
    r.lo[k] = std::max(a.lo[k], b.lo[k]);
    r.hi[k] = std::min(a.hi[k], b.hi[k]);
  }
  return r;
}

Aabb geometric_box(const Box& box, const Dims& d) {
  Aabb g;
  for (int a = 0; a < 3; ++a) {
    g.lo[a] = box.lo[a];
    g.hi[a] = std::min(box.hi[a], d[a] - 1);
  }
  return g;
}

std::array<double, 3> centre(const Aabb& box) {
  return {0.5 * (box.lo[0] + box.hi[0]), 0.5 * (box.lo[1] + box.hi[1]), 0.5 * (box.lo[2] + box.hi[2])};
}

double diagonal(const Aabb& box) {
  return std::hypot(box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]);
}

std::string spacing_problem(const std::array<double, 3>& origin,
                            const std::array<double, 3>& spacing) {
  static constexpr const char* kAxis[] = {"x", "y", "z"};
  double lo = spacing[0], hi = spacing[0];
  for (std::size_t a = 0; a < 3; ++a) {
    const std::string name = kAxis[a];
    if (!std::isfinite(origin[a])) return "the " + name + " origin " + number_text(origin[a]) +
                                          " is not a finite number";
    if (!(std::isnormal(spacing[a]) && spacing[a] > 0))
      return "the " + name + " spacing " + number_text(spacing[a]) +
             " is not a positive normal number";
    lo = std::min(lo, spacing[a]);
    hi = std::max(hi, spacing[a]);
  }
  if (hi / lo > kMaxSpacingRatio)
    return "the spacings differ by a factor " + number_text(hi / lo) + ", more than " +
           number_text(kMaxSpacingRatio) + " (the thinnest axis would draw as nothing)";
  return "";
}

}  // namespace tsp

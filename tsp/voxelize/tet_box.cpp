#include "tsp/voxelize/tet_box.h"

#include <algorithm>
#include <cmath>

namespace tsp {
namespace {

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// True when axis separates the tetrahedron from the box (centre c, half sizes h).
bool separates(const Vec3& axis, const std::array<Vec3, 4>& t, const Vec3& c, const Vec3& h) {
  const double len2 = dot(axis, axis);
  if (!(len2 > 1e-300)) return false;  // parallel edges give no axis
  double lo = dot(axis, sub(t[0], c)), hi = lo;
  for (int i = 1; i < 4; ++i) {
    const double p = dot(axis, sub(t[i], c));
    lo = std::min(lo, p);
    hi = std::max(hi, p);
  }
  const double r = h[0] * std::fabs(axis[0]) + h[1] * std::fabs(axis[1]) + h[2] * std::fabs(axis[2]);
  // A relative margin keeps touching shapes (a voxel centre on a tet face) overlapping.
  const double eps = 1e-12 * (std::fabs(lo) + std::fabs(hi) + r);
  return lo > r + eps || hi < -r - eps;
}

}  // namespace

bool tet_box_overlap(const std::array<Vec3, 4>& t, const Aabb& box) {
  Vec3 c, h;
  for (int a = 0; a < 3; ++a) {
    c[a] = 0.5 * (box.lo[a] + box.hi[a]);
    h[a] = 0.5 * (box.hi[a] - box.lo[a]);
  }
  for (int a = 0; a < 3; ++a) {
    Vec3 axis{0, 0, 0};
    axis[a] = 1;
    if (separates(axis, t, c, h)) return false;
  }
  constexpr int kFaces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (const auto& f : kFaces)
    if (separates(cross(sub(t[f[1]], t[f[0]]), sub(t[f[2]], t[f[0]])), t, c, h)) return false;
  constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (const auto& e : kEdges) {
    const Vec3 d = sub(t[e[1]], t[e[0]]);
    for (int a = 0; a < 3; ++a) {
      Vec3 axis{0, 0, 0};
      axis[a] = 1;
      if (separates(cross(axis, d), t, c, h)) return false;
    }
  }
  return true;
}

}  // namespace tsp

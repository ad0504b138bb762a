#include "tsp/frame/slicing.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "tsp/core/error.h"
#include "tsp/frame/slice_rules.h"

namespace tsp {
namespace {

constexpr double kUnitTolerance = 1e-9;
// Plane indices must stay far inside int64 and exactly representable as double.
constexpr double kMaxPlaneIndex = 1e15;
// More slices than this through one box means a spacing far below a voxel: a caller's mistake
// that would otherwise exhaust memory.
constexpr std::int64_t kMaxSlicesPerBox = std::int64_t(1) << 24;

std::string vec_str(const std::array<double, 3>& v) {
  return "(" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) +
         ")";
}

}  // namespace

Aabb geometric_box(const Box& box, const Dims& d) {
  Aabb g;
  for (int a = 0; a < 3; ++a) {
    g.lo[a] = box.lo[a];
    g.hi[a] = std::min(box.hi[a], d[a] - 1);
  }
  return g;
}

SlicePlanes SlicePlanes::toward(std::array<double, 3> dir, double spacing) {
  const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  if (!std::isfinite(len) || len == 0)
    throw UsageError("slice planes: view direction must be finite and non-zero, found " +
                     vec_str(dir));
  SlicePlanes p;
  for (int a = 0; a < 3; ++a) p.dir[a] = dir[a] / len;
  p.spacing = spacing;
  validate(p);
  return p;
}

void validate(const SlicePlanes& planes) {
  const auto& d = planes.dir;
  const double len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  if (!std::isfinite(len2) || std::abs(len2 - 1.0) > kUnitTolerance)
    throw UsageError("slice planes: view direction must be a unit vector, found " + vec_str(d));
  if (!std::isfinite(planes.spacing) || !(planes.spacing > 0))
    throw UsageError("slice planes: spacing must be positive and finite, found " +
                     std::to_string(planes.spacing));
}

namespace slice_rules {

bool make_frame(const SlicePlanes& planes, const Aabb& box, BoxFrame& f) {
  double scale = 1;
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(box.lo[a]) || !std::isfinite(box.hi[a])) return false;
    scale = std::max({scale, std::abs(box.lo[a]), std::abs(box.hi[a])});
  }
  f.tol = kRelTol * scale;
  for (int a = 0; a < 3; ++a) {
    if (!(box.hi[a] - box.lo[a] > f.tol)) return false;
    f.lo[a] = box.lo[a];
    f.hi[a] = box.hi[a];
  }
  double dmin = 0, dmax = 0;
  for (int c = 0; c < 8; ++c) {
    f.depth[c] = corner_depth(corner_coord(f, c, 0), corner_coord(f, c, 1), corner_coord(f, c, 2),
                              planes.dir);
    dmin = c == 0 ? f.depth[c] : std::min(dmin, f.depth[c]);
    dmax = c == 0 ? f.depth[c] : std::max(dmax, f.depth[c]);
  }
  const double s = planes.spacing;
  const double kf = std::floor(dmax / s - 0.5), kl = std::floor(dmin / s - 0.5);
  if (!(std::abs(kf) < kMaxPlaneIndex) || !(std::abs(kl) < kMaxPlaneIndex)) return false;
  // The floor guesses may be off by one through rounding; settle them with the exact rule.
  std::int64_t k = std::int64_t(kf);
  while (planes.depth(k) > dmax) --k;
  while (planes.depth(k + 1) <= dmax) ++k;
  f.k_first = k;
  k = std::int64_t(kl);
  while (planes.depth(k) <= dmin) ++k;
  while (planes.depth(k - 1) > dmin) --k;
  f.k_last = k;
  if (f.k_first - f.k_last + 1 > kMaxSlicesPerBox)
    throw UsageError("slice planes: spacing " + std::to_string(s) + " gives " +
                     std::to_string(f.k_first - f.k_last + 1) +
                     " slices through one box, expected at most " +
                     std::to_string(kMaxSlicesPerBox));
  return f.k_last <= f.k_first;
}

int finish_polygon(double* xyz, int n, const std::array<double, 3>& dir, double tol) {
  const double tol2 = tol * tol;
  auto dist2 = [&](int i, int j) {
    const double dx = xyz[3 * i] - xyz[3 * j], dy = xyz[3 * i + 1] - xyz[3 * j + 1],
                 dz = xyz[3 * i + 2] - xyz[3 * j + 2];
    return dx * dx + dy * dy + dz * dz;
  };
  int m = 0;
  for (int i = 0; i < n; ++i) {
    if (m > 0 && dist2(i, m - 1) <= tol2) continue;
    for (int a = 0; a < 3; ++a) xyz[3 * m + a] = xyz[3 * i + a];
    ++m;
  }
  while (m > 1 && dist2(m - 1, 0) <= tol2) --m;
  if (m < 3) return 0;
  // Twice the area, from the eye (−dir): counter-clockwise polygons give cross·dir < 0.
  double twice = 0;
  for (int i = 1; i + 1 < m; ++i) {
    double u[3], v[3];
    for (int a = 0; a < 3; ++a) {
      u[a] = xyz[3 * i + a] - xyz[a];
      v[a] = xyz[3 * (i + 1) + a] - xyz[a];
    }
    twice -= (u[1] * v[2] - u[2] * v[1]) * dir[0] + (u[2] * v[0] - u[0] * v[2]) * dir[1] +
             (u[0] * v[1] - u[1] * v[0]) * dir[2];
  }
  return 0.5 * twice > tol2 ? m : 0;
}

}  // namespace slice_rules
}  // namespace tsp

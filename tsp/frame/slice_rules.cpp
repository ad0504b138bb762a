#include "tsp/frame/slice_rules.h"

#include <string>

#include "tsp/core/error.h"

namespace tsp::slice_rules {
namespace {

// Plane indices must stay far inside int64 and exactly representable as double.
constexpr double kMaxPlaneIndex = 1e15;
// More slices than this through one box means a spacing far below a voxel: a caller's mistake
// that would otherwise exhaust memory.
constexpr std::int64_t kMaxSlicesPerBox = std::int64_t(1) << 24;

}  // namespace

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

}  // namespace tsp::slice_rules

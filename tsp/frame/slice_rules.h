// Internal to the two slicers (slicer.cpp, naive_slicer.cpp; defined in slice_rules.cpp): the numeric rules both
// apply, so that they agree exactly even when a plane passes through a corner or an edge.
// Corner c of a box has bit a set when it sits at hi on axis a (bit0 = x, bit1 = y, bit2 = z).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "tsp/frame/slicing.h"

namespace tsp::slice_rules {

/// Vertices closer than kRelTol·scale are one vertex, and a box thinner than that along an axis
/// is empty; scale = max(1, largest |coordinate| of the box).
inline constexpr double kRelTol = 1e-12;

/// A box prepared for one view: corner depths, the planes that cut it, the tolerance.
struct BoxFrame {
  std::array<double, 3> lo{}, hi{};
  std::array<double, 8> depth{};  ///< dot(corner, dir), evaluated as corner_depth()
  double tol = 0;                 ///< distance under which vertices merge
  std::int64_t k_first = 0;       ///< deepest plane cutting the box (emitted first)
  std::int64_t k_last = -1;       ///< nearest plane cutting the box; none when k_last > k_first
};

/// Coordinate of corner c on axis a.
inline double corner_coord(const BoxFrame& f, int c, int a) {
  return (c >> a) & 1 ? f.hi[a] : f.lo[a];
}

/// dot(p, dir) in a fixed order, so the same corner gets the same depth in every box sharing it,
/// and the depth never decreases when a coordinate moves the way dir points (each floating-point
/// product and sum is monotone), so computed depths respect the box's corner order.
inline double corner_depth(double x, double y, double z, const std::array<double, 3>& dir) {
  return (x * dir[0] + y * dir[1]) + z * dir[2];
}

/// Fills f for box and planes; returns false when the box is degenerate (an extent not above the
/// tolerance, or not finite) or no plane cuts it. A plane cuts the box when
/// dmin < depth(k) ≤ dmax (half-open, so a plane through a face shared by two boxes belongs to
/// exactly one of them: the nearer box, whose far face it is).
bool make_frame(const SlicePlanes& planes, const Aabb& box, BoxFrame& f);

/// Where the line along axis a through a corner at coordinate `corner_a` with depth
/// `corner_depth` meets the plane at `plane_depth` (inv_dir_a = 1/dir[a], 0 when dir[a] = 0),
/// clamped to the edge [lo_a, hi_a] so that rounding never leaves the box.
inline double edge_point(double corner_a, double corner_depth, double plane_depth, double inv_dir_a,
                         double lo_a, double hi_a) {
  const double x = corner_a + (plane_depth - corner_depth) * inv_dir_a;
  return std::min(std::max(x, lo_a), hi_a);
}

/// 1/x, or 0 when x is 0 or so small that 1/x is not finite.
inline double safe_inverse(double x) {
  const double inv = 1.0 / x;
  return std::isfinite(inv) ? inv : 0.0;
}

/// Cleans one polygon given counter-clockwise from the eye, in place: drops every vertex within
/// tol of the previously kept one (cyclically), then returns the remaining count, or 0 when
/// fewer than 3 vertices remain or the area is at most tol² (a point or a segment).
int finish_polygon(double* xyz, int n, const std::array<double, 3>& dir, double tol);

}  // namespace tsp::slice_rules

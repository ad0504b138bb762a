#include "tsp/frame/naive_slicer.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "tsp/frame/slice_rules.h"

namespace tsp {
namespace {

using Vec = std::array<double, 3>;

Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Unit vectors u, v spanning the planes with u × v = −dir (towards the eye), so angles measured
// from u towards v increase counter-clockwise seen from the eye.
void plane_basis(const Vec& dir, Vec& u, Vec& v) {
  int least = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(dir[a]) < std::abs(dir[least])) least = a;
  Vec axis{0, 0, 0};
  axis[least] = 1;
  u = cross(dir, axis);
  const double len = std::sqrt(dot(u, u));
  for (double& x : u) x /= len;
  v = cross({-dir[0], -dir[1], -dir[2]}, u);
}

}  // namespace

void naive_slice(const SlicePlanes& planes, const Aabb& box, PolygonSoup& out) {
  validate(planes);
  slice_rules::BoxFrame f;
  if (!slice_rules::make_frame(planes, box, f)) return;
  Vec inv_dir, u, v;
  for (int a = 0; a < 3; ++a) inv_dir[a] = slice_rules::safe_inverse(planes.dir[a]);
  plane_basis(planes.dir, u, v);

  constexpr int kMaxPoints = 12;
  std::array<Vec, kMaxPoints> pts;
  std::array<double, kMaxPoints> angle;
  std::array<int, kMaxPoints> idx;
  for (std::int64_t k = f.k_first; k >= f.k_last; --k) {
    const double plane = planes.depth(k);
    int n = 0;
    for (int a = 0; a < 3; ++a) {
      for (int c0 = 0; c0 < 8; ++c0) {
        if ((c0 >> a) & 1) continue;
        const int c1 = c0 | (1 << a);
        if (f.depth[c0] == f.depth[c1]) continue;  // parallel to the planes: never cut
        const int far = f.depth[c0] > f.depth[c1] ? c0 : c1, near = far ^ (1 << a);
        // Same rule as make_frame: the edge is cut when d(near) < plane ≤ d(far).
        if (!(f.depth[far] >= plane && f.depth[near] < plane)) continue;
        Vec p;
        for (int b = 0; b < 3; ++b) p[b] = slice_rules::corner_coord(f, far, b);
        p[a] = slice_rules::edge_point(p[a], f.depth[far], plane, inv_dir[a], f.lo[a], f.hi[a]);
        if (std::find(pts.begin(), pts.begin() + n, p) == pts.begin() + n) pts[n++] = p;
      }
    }
    if (n < 3) continue;
    Vec centre{0, 0, 0};
    for (int i = 0; i < n; ++i)
      for (int b = 0; b < 3; ++b) centre[b] += pts[i][b] / n;
    for (int i = 0; i < n; ++i) {
      const Vec d{pts[i][0] - centre[0], pts[i][1] - centre[1], pts[i][2] - centre[2]};
      angle[i] = std::atan2(dot(d, v), dot(d, u));
      idx[i] = i;
    }
    std::sort(idx.begin(), idx.begin() + n, [&](int a, int b) { return angle[a] < angle[b]; });
    const std::size_t base = out.xyz.size();
    out.xyz.resize(base + 3 * std::size_t(n));
    for (int i = 0; i < n; ++i)
      for (int b = 0; b < 3; ++b) out.xyz[base + 3 * i + b] = pts[idx[i]][b];
    const int m = slice_rules::finish_polygon(out.xyz.data() + base, n, planes.dir, f.tol);
    out.xyz.resize(base + 3 * std::size_t(m));
    if (m > 0) {
      out.counts.push_back(m);
      out.planes.push_back(k);
    }
  }
}

}  // namespace tsp

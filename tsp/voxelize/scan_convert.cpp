#include "tsp/voxelize/scan_convert.h"

#include <algorithm>
#include <cmath>

#include "tsp/voxelize/lattice_round.h"

namespace tsp::detail {
namespace {

struct Point3 {
  double x, y, z, v;
};
struct Point2 {
  double x, y, v;
};

// Sub-sample index range along one axis for physical [a, b], clipped to [lo, hi].
void sub_range(double a, double b, double origin, double h, int k, int lo, int hi, int& r0,
               int& r1) {
  // Sub-sample S sits at origin + ((S + ½)/k − ½)·h.
  double u = ((a - origin) / h + 0.5) * k - 0.5, w = ((b - origin) / h + 0.5) * k - 0.5;
  if (!(u <= w)) {  // NaN from overflowing coordinates: nothing
    r0 = 1;
    r1 = 0;
    return;
  }
  u = std::max(u, double(lo) - 1);  // clamped before the conversion to int
  w = std::min(w, double(hi) + 1);
  r0 = std::max(lo, first_at_or_above(u));
  r1 = std::min(hi, last_at_or_below(w));
}

double sub_coord(int s, double origin, double h, int k) { return origin + ((s + 0.5) / k - 0.5) * h; }

}  // namespace

std::int64_t scan_tet(const TetMesh& m, std::int64_t t, const VoxelGrid& g, const int t0[3],
                      const int t1[3], ScanBuffers& b) {
  const auto& q = m.tets[std::size_t(t)];
  const int k = b.k;
  Point3 p[4];
  for (int i = 0; i < 4; ++i) {
    const double* x = m.points.data() + 3 * q[std::size_t(i)];
    p[i] = {x[0], x[1], x[2],
            m.cell_values ? double(m.values[std::size_t(m.cell[std::size_t(t)])])
                          : double(m.values[std::size_t(q[std::size_t(i)])])};
  }
  double zmin = p[0].z, zmax = p[0].z;
  for (const Point3& v : p) {
    zmin = std::min(zmin, v.z);
    zmax = std::max(zmax, v.z);
  }
  int z0, z1;
  sub_range(zmin, zmax, g.origin[2], g.spacing[2], k, t0[2] * k, (t1[2] + 1) * k - 1, z0, z1);
  const Dims d = g.dims;
  std::int64_t taken = 0;
  constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (int Z = z0; Z <= z1; ++Z) {
    const double zc = sub_coord(Z, g.origin[2], g.spacing[2], k);
    // Cross-section: vertices on the plane (within a rounding margin: a sub-sample on a shared
    // vertex or edge must not fall between the tetrahedra around it) and edge crossings.
    Point2 poly[6];
    int n = 0;
    const double ez = kEdgeTolerance * g.spacing[2];
    for (const Point3& v : p)
      if (std::fabs(v.z - zc) <= ez) poly[n++] = {v.x, v.y, v.v};
    for (const auto& e : kEdges) {
      const Point3 &a = p[e[0]], &c = p[e[1]];
      if ((a.z < zc - ez && c.z > zc + ez) || (a.z > zc + ez && c.z < zc - ez)) {
        const double s = (zc - a.z) / (c.z - a.z);
        poly[n++] = {a.x + s * (c.x - a.x), a.y + s * (c.y - a.y), a.v + s * (c.v - a.v)};
      }
    }
    if (n == 0) continue;
    // Order around the centroid so consecutive points are the polygon's edges.
    double cx = 0, cy = 0;
    for (int i = 0; i < n; ++i) {
      cx += poly[i].x;
      cy += poly[i].y;
    }
    cx /= n;
    cy /= n;
    std::sort(poly, poly + n, [&](const Point2& a, const Point2& c) {
      return std::atan2(a.y - cy, a.x - cx) < std::atan2(c.y - cy, c.x - cx);
    });
    double ymin = poly[0].y, ymax = poly[0].y;
    for (int i = 1; i < n; ++i) {
      ymin = std::min(ymin, poly[i].y);
      ymax = std::max(ymax, poly[i].y);
    }
    int y0, y1;
    sub_range(ymin, ymax, g.origin[1], g.spacing[1], k, t0[1] * k, (t1[1] + 1) * k - 1, y0, y1);
    for (int Y = y0; Y <= y1; ++Y) {
      const double yc = sub_coord(Y, g.origin[1], g.spacing[1], k);
      // The span: where the polygon's edges (and points) meet the row.
      double xa = INFINITY, xb = -INFINITY, va = 0, vb = 0;
      auto extend = [&](double x, double v) {
        if (x < xa) {
          xa = x;
          va = v;
        }
        if (x > xb) {
          xb = x;
          vb = v;
        }
      };
      const double ey = kEdgeTolerance * g.spacing[1];
      for (int i = 0; i < n; ++i) {
        const Point2 &a = poly[i], &c = poly[(i + 1) % n];
        if (std::fabs(a.y - yc) <= ey) extend(a.x, a.v);
        if ((a.y < yc - ey && c.y > yc + ey) || (a.y > yc + ey && c.y < yc - ey)) {
          const double s = (yc - a.y) / (c.y - a.y);
          extend(a.x + s * (c.x - a.x), a.v + s * (c.v - a.v));
        }
      }
      if (!(xa <= xb)) continue;
      int x0, x1;
      sub_range(xa, xb, g.origin[0], g.spacing[0], k, t0[0] * k, (t1[0] + 1) * k - 1, x0, x1);
      if (x0 > x1) continue;
      // Incremental along the span.
      const double slope = xb > xa ? (vb - va) / (xb - xa) : 0;
      const double dx = g.spacing[0] / k;
      double v = va + (sub_coord(x0, g.origin[0], g.spacing[0], k) - xa) * slope;
      const double dv = slope * dx;
      const std::int64_t row =
          std::int64_t(d.x) * (Y / k + std::int64_t(d.y) * (Z / k));
      const int bit_yz = k * ((Y % k) + k * (Z % k));
      for (int X = x0; X <= x1; ++X, v += dv) {
        const std::size_t i = std::size_t(row + X / k);
        const std::uint64_t bit = std::uint64_t(1) << (X % k + bit_yz);
        if (b.taken[i] & bit) continue;
        b.taken[i] |= bit;
        b.sum[i] += v;
        ++taken;
      }
    }
  }
  return taken;
}

}  // namespace tsp::detail

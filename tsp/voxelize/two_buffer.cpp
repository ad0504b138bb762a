#include "tsp/voxelize/two_buffer.h"

#include <algorithm>
#include <cmath>

#include "tsp/voxelize/lattice_round.h"

namespace tsp::detail {
namespace {

// A vertex in the pass's lattice units: sample (i, j, k) of the pass sits at (i, j, k).
struct Vertex {
  double x, y, z, v;
};

// One buffer over the tetrahedron's pixel rectangle: depth and value per pixel, and whether set.
struct Buffer {
  int i0 = 0, j0 = 0, w = 0, h = 0;
  std::vector<double> z, v;
  std::vector<std::uint8_t> set;
  void reset(int ii0, int jj0, int ww, int hh) {
    i0 = ii0;
    j0 = jj0;
    w = ww;
    h = hh;
    const std::size_t n = std::size_t(w) * std::size_t(h);
    z.resize(n);
    v.resize(n);
    set.assign(n, 0);
  }
};

std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// An edge walked one scan line at a time (form_buffers): x, depth and value at row j, stepped.
struct EdgeWalk {
  double x, z, v, dx, dz, dv;
  EdgeWalk(const Vertex& a, const Vertex& b, int j) {
    const double dy = b.y - a.y;
    dx = dy != 0 ? (b.x - a.x) / dy : 0;
    dz = dy != 0 ? (b.z - a.z) / dy : 0;
    dv = dy != 0 ? (b.v - a.v) / dy : 0;
    const double s = j - a.y;
    x = a.x + s * dx;
    z = a.z + s * dz;
    v = a.v + s * dv;
  }
  void step() {
    x += dx;
    z += dz;
    v += dv;
  }
};

// Scan-converts triangle (a, b, c) into buf: per row its extent from the edges, along the row
// depth and value stepped (scan_convert). Rows and columns outside buf are skipped.
void scan_convert(Vertex a, Vertex b, Vertex c, Buffer& buf) {
  if (a.y > b.y) std::swap(a, b);
  if (b.y > c.y) std::swap(b, c);
  if (a.y > b.y) std::swap(a, b);
  // (Clamped to the buffer before the conversion to int: a vertex may lie far away.)
  const int j0 = std::max(buf.j0, first_at_or_above(std::max(a.y, double(buf.j0) - 1)));
  const int j1 = std::min(buf.j0 + buf.h - 1, last_at_or_below(std::min(c.y, double(buf.j0 + buf.h))));
  if (j0 > j1) return;
  EdgeWalk longest(a, c, j0), upper(a, b, j0), lower(b, c, j0);
  for (int j = j0; j <= j1; ++j, longest.step(), upper.step(), lower.step()) {
    // The short edge this row crosses: a→b below b, b→c above (either at b itself).
    const EdgeWalk& other = j < b.y ? upper : lower;
    const bool flat_a = b.y - a.y <= kEdgeTolerance, flat_c = c.y - b.y <= kEdgeTolerance;
    const EdgeWalk& e = flat_a ? lower : flat_c ? upper : other;
    double xl = longest.x, zl = longest.z, vl = longest.v;
    double xr = e.x, zr = e.z, vr = e.v;
    if (c.y - a.y <= kEdgeTolerance) {  // the whole triangle on one row: its x extent
      xl = std::min({a.x, b.x, c.x});
      xr = std::max({a.x, b.x, c.x});
      zl = zr = (a.z + b.z + c.z) / 3;  // (edge-on to the rows: depth ill-defined, rarely hit)
      vl = vr = (a.v + b.v + c.v) / 3;
    }
    if (xl > xr) {
      std::swap(xl, xr);
      std::swap(zl, zr);
      std::swap(vl, vr);
    }
    if (!(xl <= xr)) continue;  // (NaN)
    const int i0 = std::max(buf.i0, first_at_or_above(std::max(xl, double(buf.i0) - 1)));
    const int i1 = std::min(buf.i0 + buf.w - 1, last_at_or_below(std::min(xr, double(buf.i0 + buf.w))));
    if (i0 > i1) continue;
    const double w = xr - xl;
    const double dz = w > 0 ? (zr - zl) / w : 0, dv = w > 0 ? (vr - vl) / w : 0;
    double z = zl + (i0 - xl) * dz, v = vl + (i0 - xl) * dv;
    std::size_t at = std::size_t(j - buf.j0) * std::size_t(buf.w) + std::size_t(i0 - buf.i0);
    for (int i = i0; i <= i1; ++i, ++at, z += dz, v += dv) {
      if (buf.set[at]) continue;  // a pixel on the edge two faces share: the first keeps it
      buf.set[at] = 1;
      buf.z[at] = z;
      buf.v[at] = v;
    }
  }
}

}  // namespace

std::vector<std::array<double, 3>> pass_offsets(int k, bool jitter) {
  std::vector<std::array<double, 3>> out;
  for (int sz = 0; sz < k; ++sz)
    for (int sy = 0; sy < k; ++sy)
      for (int sx = 0; sx < k; ++sx) {
        const int s[3] = {sx, sy, sz};
        std::array<double, 3> o{};
        const std::uint64_t column = std::uint64_t(sy * k + sx), pass = out.size();
        for (int a = 0; a < 3; ++a) {
          o[std::size_t(a)] = (s[a] + 0.5) / k - 0.5;
          if (jitter) {  // x and y by the sub-pixel, z by the pass
            const std::uint64_t h = splitmix((a < 2 ? column : pass) * 3 + std::uint64_t(a));
            const double u = double(h >> 11) * 0x1.0p-53 * 2 - 1;  // in [−1, 1)
            o[std::size_t(a)] += u * kJitterShare / k;
          }
        }
        out.push_back(o);
      }
  return out;
}

std::int64_t two_buffer_tet(const TetMesh& m, std::int64_t t, const VoxelGrid& g, const int t0[3],
                            const int t1[3], PassBuffers& b) {
  const auto& q = m.tets[std::size_t(t)];
  double p[4][4];  // physical x, y, z and value
  for (int i = 0; i < 4; ++i) {
    const double* x = m.points.data() + 3 * q[std::size_t(i)];
    for (int a = 0; a < 3; ++a) p[i][a] = x[a];
    p[i][3] = m.cell_values ? double(m.values[std::size_t(m.cell[std::size_t(t)])])
                            : double(m.values[std::size_t(q[std::size_t(i)])]);
  }
  // Faces with their opposite vertex; each faces the viewer (looking along +z) when its outward
  // normal points to −z. The orientation does not depend on the pass (a shift).
  constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
  int side[4];  // −1 front, +1 back, 0 edge-on
  for (int f = 0; f < 4; ++f) {
    const double* A = p[kFaces[f][0]];
    const double* B = p[kFaces[f][1]];
    const double* C = p[kFaces[f][2]];
    const double* D = p[kFaces[f][3]];
    const double u[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]};
    const double w[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
    double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    if (n[0] * (D[0] - A[0]) + n[1] * (D[1] - A[1]) + n[2] * (D[2] - A[2]) > 0)
      for (double& c : n) c = -c;  // outward
    side[f] = n[2] < 0 ? -1 : n[2] > 0 ? 1 : 0;
  }
  thread_local Buffer front, back;
  const Dims d = g.dims;
  std::int64_t taken = 0;
  const int k = b.k;
  const std::size_t columns = std::size_t(k) * std::size_t(k);
  for (std::size_t column = 0; column < columns; ++column) {
    // The sub-pixel's buffers, in its lattice: sample (i, j) at (i, j); depth unshifted.
    const std::array<double, 3>& o = b.offset[column];
    Vertex v[4];
    for (int i = 0; i < 4; ++i)
      v[i] = {(p[i][0] - g.origin[0]) / g.spacing[0] - o[0],
              (p[i][1] - g.origin[1]) / g.spacing[1] - o[1],
              (p[i][2] - g.origin[2]) / g.spacing[2], p[i][3]};
    double lo[2] = {v[0].x, v[0].y}, hi[2] = {v[0].x, v[0].y};
    for (const Vertex& x : v) {
      lo[0] = std::min(lo[0], x.x);
      hi[0] = std::max(hi[0], x.x);
      lo[1] = std::min(lo[1], x.y);
      hi[1] = std::max(hi[1], x.y);
    }
    if (!(lo[0] <= hi[0]) || !(lo[1] <= hi[1])) continue;  // NaN
    const int i0 = std::max(t0[0], first_at_or_above(std::max(lo[0], double(t0[0]) - 1)));
    const int i1 = std::min(t1[0], last_at_or_below(std::min(hi[0], double(t1[0]) + 1)));
    const int j0 = std::max(t0[1], first_at_or_above(std::max(lo[1], double(t0[1]) - 1)));
    const int j1 = std::min(t1[1], last_at_or_below(std::min(hi[1], double(t1[1]) + 1)));
    if (i0 > i1 || j0 > j1) continue;
    front.reset(i0, j0, i1 - i0 + 1, j1 - j0 + 1);
    back.reset(i0, j0, i1 - i0 + 1, j1 - j0 + 1);
    for (int f = 0; f < 4; ++f)
      if (side[f] != 0)
        scan_convert(v[kFaces[f][0]], v[kFaces[f][1]], v[kFaces[f][2]], side[f] < 0 ? front : back);
    // Between the two buffers, for each pass of this sub-pixel (its own depth offset): every
    // voxel of a column from the front depth to the back depth, the value stepped from the
    // front value.
    const std::size_t slab = std::size_t(d.x) * std::size_t(d.y);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const std::size_t at = std::size_t(j - j0) * std::size_t(front.w) + std::size_t(i - i0);
        if (!front.set[at] || !back.set[at]) continue;
        double zf = front.z[at], zb = back.z[at], vf = front.v[at], vb = back.v[at];
        if (zf > zb) {
          std::swap(zf, zb);
          std::swap(vf, vb);
        }
        if (!(zf <= zb)) continue;  // (NaN)
        const double incr = zb > zf ? (vb - vf) / (zb - zf) : 0;
        for (std::size_t pass = column; pass < b.offset.size(); pass += columns) {
          const double oz = b.offset[pass][2];
          const int k0 = std::max(t0[2], first_at_or_above(std::max(zf - oz, double(t0[2]) - 1)));
          const int k1 = std::min(t1[2], last_at_or_below(std::min(zb - oz, double(t1[2]) + 1)));
          if (k0 > k1) continue;
          const std::size_t word = pass / 64;
          const std::uint64_t bit = std::uint64_t(1) << (pass % 64);
          double value = vf + (k0 + oz - zf) * incr;
          std::size_t voxel = std::size_t(i + std::int64_t(d.x) * (j + std::int64_t(d.y) * k0));
          for (int kk = k0; kk <= k1; ++kk, voxel += slab, value += incr) {
            std::uint64_t& mask = b.taken[voxel][word];
            if (mask & bit) continue;
            mask |= bit;
            b.sum[voxel] += value;
            ++taken;
          }
        }
      }
  }
  return taken;
}

}  // namespace tsp::detail

#include "tsp/voxelize/voxelizer.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <vector>

#include "tsp/core/parallel_for.h"
#include "tsp/voxelize/tet_box.h"

namespace tsp {
namespace {

// Voxels per tile edge: a tile's bins stay small and tiles spread over the workers.
constexpr int kTile = 16;
// Barycentric coordinates down to −kInsideTolerance count as inside: voxel centres on a face
// shared by two tetrahedra (or on the mesh's boundary) are found despite rounding.
constexpr double kInsideTolerance = 1e-9;
// Tetrahedra whose volume is below this fraction of their bounding box's are skipped.
constexpr double kDegenerate = 1e-14;

struct TileGrid {
  std::array<int, 3> n{};  // tiles per axis
  int count() const { return n[0] * n[1] * n[2]; }
};

Vec3 point(const TetMesh& m, std::int64_t p) {
  const double* x = m.points.data() + 3 * p;
  return {x[0], x[1], x[2]};
}

// Voxel index range [lo, hi] whose centres fall inside [a, b] along axis ax (clamped).
void voxel_range(double a, double b, const VoxelGrid& g, int ax, int& lo, int& hi) {
  const double u = (a - g.origin[ax]) / g.spacing[ax], v = (b - g.origin[ax]) / g.spacing[ax];
  lo = std::max(0, int(std::ceil(u - 1e-9)));
  hi = std::min(g.dims[ax] - 1, int(std::floor(v + 1e-9)));
}

}  // namespace

VoxelizeStats voxelize(const TetMesh& mesh, const VoxelGrid& grid, std::span<float> values,
                       std::span<std::uint8_t> inside, int threads) {
  const Dims d = grid.dims;
  assert(std::int64_t(values.size()) == d.count() && inside.size() == values.size());
  std::fill(values.begin(), values.end(), 0.f);
  std::fill(inside.begin(), inside.end(), std::uint8_t(0));
  VoxelizeStats stats;
  stats.tets = std::int64_t(mesh.tets.size());
  TileGrid tiles;
  for (int a = 0; a < 3; ++a) tiles.n[a] = (d[a] + kTile - 1) / kTile;

  // Bin: each tet into the tiles whose voxel centres its box spans and that it overlaps.
  std::vector<std::vector<std::int64_t>> bins(std::size_t(tiles.count()));
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    std::array<Vec3, 4> v;
    for (int i = 0; i < 4; ++i) v[i] = point(mesh, mesh.tets[t][std::size_t(i)]);
    int lo[3], hi[3];
    bool empty = false;
    for (int a = 0; a < 3; ++a) {
      double mn = v[0][a], mx = v[0][a];
      for (int i = 1; i < 4; ++i) {
        mn = std::min(mn, v[i][a]);
        mx = std::max(mx, v[i][a]);
      }
      voxel_range(mn, mx, grid, a, lo[a], hi[a]);
      empty |= lo[a] > hi[a];
    }
    if (empty) continue;
    for (int tz = lo[2] / kTile; tz <= hi[2] / kTile; ++tz)
      for (int ty = lo[1] / kTile; ty <= hi[1] / kTile; ++ty)
        for (int tx = lo[0] / kTile; tx <= hi[0] / kTile; ++tx) {
          const int tl[3] = {tx, ty, tz};
          bool whole = true;  // the tet's voxel box lies in this one tile: no test needed
          Aabb box;
          for (int a = 0; a < 3; ++a) {
            const int v0 = std::max(lo[a], tl[a] * kTile);
            const int v1 = std::min(hi[a], tl[a] * kTile + kTile - 1);
            whole &= v0 == lo[a] && v1 == hi[a];
            box.lo[a] = grid.origin[a] + v0 * grid.spacing[a];
            box.hi[a] = grid.origin[a] + v1 * grid.spacing[a];
          }
          if (!whole) {
            ++stats.tile_tests;
            if (!tet_box_overlap(v, box)) continue;
          }
          ++stats.tile_entries;
          bins[std::size_t(tx + tiles.n[0] * (ty + tiles.n[1] * tz))].push_back(
              std::int64_t(t));
        }
  }

  // Sample: tiles in parallel; in each, tets in index order, first containing tet wins.
  std::vector<std::int64_t> inside_count(std::size_t(tiles.count()), 0);
  parallel_for(tiles.count(), 1, threads, [&](int, std::int64_t first, std::int64_t last) {
    for (std::int64_t ti = first; ti < last; ++ti) {
      const int tl[3] = {int(ti % tiles.n[0]), int(ti / tiles.n[0] % tiles.n[1]),
                         int(ti / (std::int64_t(tiles.n[0]) * tiles.n[1]))};
      int t0[3], t1[3];
      for (int a = 0; a < 3; ++a) {
        t0[a] = tl[a] * kTile;
        t1[a] = std::min(d[a] - 1, t0[a] + kTile - 1);
      }
      for (std::int64_t t : bins[std::size_t(ti)]) {
        const auto& q = mesh.tets[std::size_t(t)];
        const Vec3 p0 = point(mesh, q[0]), p1 = point(mesh, q[1]), p2 = point(mesh, q[2]),
                   p3 = point(mesh, q[3]);
        // Barycentric coordinates λ1..3 = M⁻¹ (x − p0) with M = [p1 − p0, p2 − p0, p3 − p0].
        double m[3][3];
        for (int a = 0; a < 3; ++a) {
          m[a][0] = p1[a] - p0[a];
          m[a][1] = p2[a] - p0[a];
          m[a][2] = p3[a] - p0[a];
        }
        const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        int lo[3], hi[3];
        double ext = 1;
        for (int a = 0; a < 3; ++a) {
          double mn = std::min({p0[a], p1[a], p2[a], p3[a]});
          double mx = std::max({p0[a], p1[a], p2[a], p3[a]});
          ext *= mx - mn;
          voxel_range(mn, mx, grid, a, lo[a], hi[a]);
          lo[a] = std::max(lo[a], t0[a]);
          hi[a] = std::min(hi[a], t1[a]);
        }
        if (!(std::fabs(det) > kDegenerate * ext)) continue;
        const double inv = 1.0 / det;
        double r[3][3];  // inverse of m
        r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * inv;
        r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv;
        r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv;
        r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * inv;
        r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv;
        r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv;
        r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * inv;
        r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv;
        r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv;
        const double v0 = mesh.cell_values ? 0 : mesh.values[std::size_t(q[0])];
        const double v1 = mesh.cell_values ? 0 : mesh.values[std::size_t(q[1])];
        const double v2 = mesh.cell_values ? 0 : mesh.values[std::size_t(q[2])];
        const double v3 = mesh.cell_values ? 0 : mesh.values[std::size_t(q[3])];
        const float cell_value =
            mesh.cell_values ? mesh.values[std::size_t(mesh.cell[std::size_t(t)])] : 0.f;
        for (int z = lo[2]; z <= hi[2]; ++z)
          for (int y = lo[1]; y <= hi[1]; ++y) {
            const std::int64_t row = std::int64_t(d.x) * (y + std::int64_t(d.y) * z);
            const double dy = grid.origin[1] + y * grid.spacing[1] - p0[1];
            const double dz = grid.origin[2] + z * grid.spacing[2] - p0[2];
            for (int x = lo[0]; x <= hi[0]; ++x) {
              const std::size_t i = std::size_t(row + x);
              if (inside[i]) continue;
              const double dx = grid.origin[0] + x * grid.spacing[0] - p0[0];
              const double l1 = r[0][0] * dx + r[0][1] * dy + r[0][2] * dz;
              const double l2 = r[1][0] * dx + r[1][1] * dy + r[1][2] * dz;
              const double l3 = r[2][0] * dx + r[2][1] * dy + r[2][2] * dz;
              const double l0 = 1.0 - l1 - l2 - l3;
              if (l0 < -kInsideTolerance || l1 < -kInsideTolerance || l2 < -kInsideTolerance ||
                  l3 < -kInsideTolerance)
                continue;
              values[i] = mesh.cell_values ? cell_value
                                           : float(l0 * v0 + l1 * v1 + l2 * v2 + l3 * v3);
              inside[i] = 1;
              ++inside_count[std::size_t(ti)];
            }
          }
      }
    }
  });
  for (std::int64_t c : inside_count) stats.inside += c;
  pad_outside(values, inside, d);
  return stats;
}

void pad_outside(std::span<float> values, std::span<const std::uint8_t> inside, Dims d) {
  const std::size_t n = values.size();
  std::vector<std::int64_t> queue;
  std::vector<std::uint8_t> reached(inside.begin(), inside.end());
  for (std::size_t i = 0; i < n; ++i)
    if (inside[i]) queue.push_back(std::int64_t(i));
  if (queue.empty()) return;
  const std::int64_t sx = 1, sy = d.x, sz = std::int64_t(d.x) * d.y;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::int64_t i = queue[head];
    const int x = int(i % d.x), y = int(i / sy % d.y), z = int(i / sz);
    const std::int64_t nb[6] = {x > 0 ? i - sx : -1,       x + 1 < d.x ? i + sx : -1,
                                y > 0 ? i - sy : -1,       y + 1 < d.y ? i + sy : -1,
                                z > 0 ? i - sz : -1,       z + 1 < d.z ? i + sz : -1};
    for (std::int64_t j : nb) {
      if (j < 0 || reached[std::size_t(j)]) continue;
      reached[std::size_t(j)] = 1;
      values[std::size_t(j)] = values[std::size_t(i)];
      queue.push_back(j);
    }
  }
}

}  // namespace tsp

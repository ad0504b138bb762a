#include "tsp/voxelize/voxelizer.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/core/parallel_for.h"
#include "tsp/voxelize/mat3.h"
#include "tsp/voxelize/scan_convert.h"
#include "tsp/voxelize/two_buffer.h"
#include "tsp/voxelize/tet_box.h"

namespace tsp {
namespace {

// Tiles are bars of whole rows (cells stored in row order stay together in memory while a tile
// is sampled) of about kTileVoxels voxels with a near-square cross-section (a cell spans few
// tiles), at least kTilesPerWorker per worker.
constexpr std::int64_t kTileVoxels = 1 << 16;
constexpr int kTilesPerWorker = 4;
// Barycentric (or parametric) coordinates down to −kInsideTolerance count as inside: voxel
// centres on a face shared by two cells (or on the mesh's boundary) are found despite rounding.
constexpr double kInsideTolerance = 1e-9;
// Tetrahedra whose volume is below this fraction of their bounding box's are skipped.
constexpr double kDegenerate = 1e-14;
// Newton's method on a hexahedron's trilinear map: iterations, and the step in parametric
// coordinates that counts as converged.
constexpr int kNewtonIterations = 16;
constexpr double kNewtonTolerance = 1e-12;
// Work found while sampling (Newton iterations) is added to the shared visit count in batches
// of at least this many visits, and the budget checked then.
constexpr std::int64_t kChargeBatch = 1 << 14;
// Binning runs over this many contiguous blocks of cells per worker (their bins are read in
// block order, so every bin stays in cell order).
constexpr int kBinBlocksPerWorker = 4;
// VTK hexahedron corners in parametric coordinates.
constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

struct TileGrid {
  std::array<int, 3> size{};  // voxels per tile edge
  std::array<int, 3> n{};     // tiles per axis
  int count() const { return n[0] * n[1] * n[2]; }
};

// Bars: whole rows, a cross-section of about kTileVoxels / d.x voxels as square as the grid
// allows, thinned along z while there are fewer than kTilesPerWorker tiles per worker.
TileGrid bar_tiles(Dims d, int workers) {
  TileGrid t;
  const int edge = std::max(1, int(std::sqrt(double(kTileVoxels) / d.x)));
  t.size = {d.x, std::min(edge, d.y), 0};
  t.size[2] = int(std::clamp<std::int64_t>(kTileVoxels / (std::int64_t(d.x) * t.size[1]), 1, d.z));
  const auto count = [&] {
    for (int a = 0; a < 3; ++a) t.n[a] = (d[a] + t.size[a] - 1) / t.size[a];
    return t.count();
  };
  while (count() < workers * kTilesPerWorker && t.size[2] > 1) t.size[2] = (t.size[2] + 1) / 2;
  return t;
}

// ceil and floor of x in [−2, 2³¹): without SSE4.1 std::ceil is a library call, and this runs
// for every cell.
inline int ceil_int(double x) {
  const int i = int(x);
  return i + (x > i);
}
inline int floor_int(double x) {
  const int i = int(x);
  return i - (x < i);
}

// Voxel index range [lo, hi] whose centres fall inside [a, b] along axis ax (clamped).
inline void voxel_range(double a, double b, const VoxelGrid& g, int ax, int& lo, int& hi) {
  const double inv = 1.0 / g.spacing[ax];  // hoisted by the compiler across the inlined calls
  double u = (a - g.origin[ax]) * inv, v = (b - g.origin[ax]) * inv;
  if (!(u <= v)) {  // NaN from overflowing coordinates: nothing
    lo = 1;
    hi = 0;
    return;
  }
  // Clamped before the conversion to int (a box far outside the grid stays empty).
  u = std::max(u, -1.0);
  v = std::min(v, double(g.dims[ax]));
  lo = std::max(0, ceil_int(u - 1e-9));
  hi = std::min(g.dims[ax] - 1, floor_int(v + 1e-9));
}

// A bin entry: t ≥ 0 is tetrahedron t, −1 − c the whole hexahedron c.
using Item = std::int64_t;

// One worker's Newton work while it samples hexahedra: visits not yet added to the shared
// count, and iterations run (for the stats), all and those of solves that found no voxel.
struct HexWork {
  std::int64_t pending = 0;
  std::int64_t iterations = 0;
  std::int64_t missed = 0;
  // Adds a row's iterations; only those that found nothing are charged (the others find each
  // voxel once, work bounded by the grid).
  void add(std::int64_t all, std::int64_t wasted) {
    iterations += all;
    missed += wasted;
    pending += wasted * kNewtonIterationVisits;
  }
};

struct Voxelizer {
  const Mesh& mesh;
  const TetMesh& tets;
  const VoxelGrid& grid;
  std::span<float> values;
  std::span<std::uint8_t> inside;
  bool whole_hex;
  TileGrid tiles;
  // How far a voxel's sub-samples reach from its centre (the scan voxelizer's K > 1): cells
  // are binned to the voxels whose sub-samples, not only centres, they may hold.
  std::array<double, 3> margin{0, 0, 0};
  // The visits binned so far over all workers, and the most allowed (kVisitsPerItem), each
  // weighted by its cost: a binned visit costs visit_cost (K³ for the scan and two-buffer
  // voxelizers, whose every visit samples K³ sub-samples or passes), a Newton iteration that
  // finds no voxel kNewtonIterationVisits more, counted as it runs.
  std::int64_t budget = 0;
  std::int64_t visit_cost = 1;
  mutable std::atomic<std::int64_t> visits{0};
  bool over_budget() const { return visits.load(std::memory_order_relaxed) > budget; }
  // Adds the work's pending visits to the shared count once they make a batch (or with force);
  // true when the budget is spent.
  bool charge(HexWork& work, bool force = false) const {
    if (work.pending >= kChargeBatch || (force && work.pending > 0)) {
      visits.fetch_add(work.pending, std::memory_order_relaxed);
      work.pending = 0;
    }
    return over_budget();
  }

  Vec3 tet_point(std::int64_t p) const {
    const double* x = tets.points.data() + 3 * p;
    return {x[0], x[1], x[2]};
  }
  // Hexahedron c's 8 point indices in VTK hexahedron order.
  void hex_points(std::int64_t c, std::int64_t out[8]) const {
    const std::int64_t* g = mesh.connectivity.data() + mesh.offsets[std::size_t(c)];
    const bool voxel = mesh.types[std::size_t(c)] == CellType::voxel;
    for (int i = 0; i < 8; ++i) out[i] = g[voxel ? kVoxelToHex[i] : i];
  }

  // Adds item to the bins of the tiles its voxel box [lo, hi] spans (tetrahedra: only those the
  // separating-axis test keeps).
  void bin(Item item, const int lo[3], const int hi[3], const std::array<Vec3, 4>* tet,
           std::vector<std::vector<Item>>& bins, VoxelizeStats& st) const {
    const auto& ts = tiles.size;
    std::int64_t item_visits = 0;
    for (int tz = lo[2] / ts[2]; tz <= hi[2] / ts[2]; ++tz)
      for (int ty = lo[1] / ts[1]; ty <= hi[1] / ts[1]; ++ty)
        for (int tx = lo[0] / ts[0]; tx <= hi[0] / ts[0]; ++tx) {
          const int tl[3] = {tx, ty, tz};
          bool whole = true;  // the voxel box lies in this one tile: no test needed
          Aabb box;
          for (int a = 0; a < 3; ++a) {
            const int v0 = std::max(lo[a], tl[a] * ts[a]);
            const int v1 = std::min(hi[a], tl[a] * ts[a] + ts[a] - 1);
            whole &= v0 == lo[a] && v1 == hi[a];
            box.lo[a] = grid.origin[a] + v0 * grid.spacing[a] - margin[a];
            box.hi[a] = grid.origin[a] + v1 * grid.spacing[a] + margin[a];
          }
          if (!whole && tet) {
            ++st.tile_tests;
            if (!tet_box_overlap(*tet, box)) continue;
          }
          ++st.tile_entries;
          std::int64_t n = 1;
          for (int a = 0; a < 3; ++a)
            n *= std::min(hi[a], tl[a] * ts[a] + ts[a] - 1) - std::max(lo[a], tl[a] * ts[a]) + 1;
          item_visits += n;
          bins[std::size_t(tx + tiles.n[0] * (ty + tiles.n[1] * tz))].push_back(item);
        }
    st.visits += item_visits;
    visits.fetch_add(item_visits * visit_cost, std::memory_order_relaxed);
  }

  // Bins the cells [first, last) (tetrahedra [tet_first, …) belong to them in order).
  void bin_cells(std::int64_t first, std::int64_t last, std::int64_t tet_first,
                 std::vector<std::vector<Item>>& bins, VoxelizeStats& st) const {
    std::int64_t t = tet_first;
    for (std::int64_t c = first; c < last && !over_budget(); ++c) {
      if (whole_hex && is_hexahedral(mesh.types[std::size_t(c)])) {
        std::int64_t g[8];
        hex_points(c, g);
        double mn[3], mx[3];
        for (int a = 0; a < 3; ++a) mn[a] = mx[a] = mesh.points[std::size_t(3 * g[0] + a)];
        for (int i = 1; i < 8; ++i)
          for (int a = 0; a < 3; ++a) {
            mn[a] = std::min(mn[a], mesh.points[std::size_t(3 * g[i] + a)]);
            mx[a] = std::max(mx[a], mesh.points[std::size_t(3 * g[i] + a)]);
          }
        int lo[3], hi[3];
        bool empty = false;
        for (int a = 0; a < 3; ++a) {
          voxel_range(mn[a], mx[a], grid, a, lo[a], hi[a]);
          empty |= lo[a] > hi[a];
        }
        if (!empty) bin(-1 - c, lo, hi, nullptr, bins, st);
        continue;
      }
      for (; t < std::int64_t(tets.tets.size()) && tets.cell[std::size_t(t)] == c; ++t) {
        std::array<Vec3, 4> v;
        for (int i = 0; i < 4; ++i) v[std::size_t(i)] = tet_point(tets.tets[std::size_t(t)][std::size_t(i)]);
        int lo[3], hi[3];
        bool empty = false;
        for (int a = 0; a < 3; ++a) {
          const double mn = std::min({v[0][a], v[1][a], v[2][a], v[3][a]});
          const double mx = std::max({v[0][a], v[1][a], v[2][a], v[3][a]});
          voxel_range(mn - margin[a], mx + margin[a], grid, a, lo[a], hi[a]);
          empty |= lo[a] > hi[a];
        }
        if (!empty) bin(t, lo, hi, &v, bins, st);
      }
    }
  }

  // Voxel range of the box [mn, mx] clipped to tile [t0, t1]; false when empty.
  bool clipped_range(const double mn[3], const double mx[3], const int t0[3], const int t1[3],
                     int lo[3], int hi[3]) const {
    for (int a = 0; a < 3; ++a) {
      voxel_range(mn[a], mx[a], grid, a, lo[a], hi[a]);
      lo[a] = std::max(lo[a], t0[a]);
      hi[a] = std::min(hi[a], t1[a]);
      if (lo[a] > hi[a]) return false;
    }
    return true;
  }

  double voxel_coord(int a, int i) const { return grid.origin[a] + i * grid.spacing[a]; }

  std::int64_t sample_tet(std::int64_t t, const int t0[3], const int t1[3]) const {
    const auto& q = tets.tets[std::size_t(t)];
    const Vec3 p0 = tet_point(q[0]), p1 = tet_point(q[1]), p2 = tet_point(q[2]), p3 = tet_point(q[3]);
    double mn[3], mx[3], ext = 1;
    for (int a = 0; a < 3; ++a) {
      mn[a] = std::min({p0[a], p1[a], p2[a], p3[a]});
      mx[a] = std::max({p0[a], p1[a], p2[a], p3[a]});
      ext *= mx[a] - mn[a];
    }
    int lo[3], hi[3];
    if (!clipped_range(mn, mx, t0, t1, lo, hi)) return 0;
    // Barycentric coordinates λ1..3 = M⁻¹ (x − p0) with M = [p1 − p0, p2 − p0, p3 − p0].
    double m[3][3];
    for (int a = 0; a < 3; ++a) {
      m[a][0] = p1[a] - p0[a];
      m[a][1] = p2[a] - p0[a];
      m[a][2] = p3[a] - p0[a];
    }
    double r[3][3];  // inverse of m
    if (!detail::inverse3(m, r, kDegenerate * ext)) return 0;
    const bool cells = tets.cell_values;
    const double v0 = cells ? 0 : tets.values[std::size_t(q[0])];
    const double v1 = cells ? 0 : tets.values[std::size_t(q[1])];
    const double v2 = cells ? 0 : tets.values[std::size_t(q[2])];
    const double v3 = cells ? 0 : tets.values[std::size_t(q[3])];
    const float cell_value = cells ? tets.values[std::size_t(tets.cell[std::size_t(t)])] : 0.f;
    const Dims d = grid.dims;
    std::int64_t found = 0;
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y) {
        const std::int64_t row = std::int64_t(d.x) * (y + std::int64_t(d.y) * z);
        const double dy = voxel_coord(1, y) - p0[1], dz = voxel_coord(2, z) - p0[2];
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const std::size_t i = std::size_t(row + x);
          if (inside[i]) continue;
          const double dx = voxel_coord(0, x) - p0[0];
          const double l1 = r[0][0] * dx + r[0][1] * dy + r[0][2] * dz;
          const double l2 = r[1][0] * dx + r[1][1] * dy + r[1][2] * dz;
          const double l3 = r[2][0] * dx + r[2][1] * dy + r[2][2] * dz;
          const double l0 = 1.0 - l1 - l2 - l3;
          if (l0 < -kInsideTolerance || l1 < -kInsideTolerance || l2 < -kInsideTolerance ||
              l3 < -kInsideTolerance)
            continue;
          values[i] = cells ? cell_value : float(l0 * v0 + l1 * v1 + l2 * v2 + l3 * v3);
          inside[i] = 1;
          ++found;
        }
      }
    return found;
  }

  // Samples hexahedron c's voxels in tile [t0, t1], charging its Newton iterations to work;
  // stops early when the budget is spent.
  std::int64_t sample_hex(std::int64_t c, const int t0[3], const int t1[3], HexWork& work) const {
    std::int64_t g[8];
    hex_points(c, g);
    double x[8][3], mn[3], mx[3];
    for (int i = 0; i < 8; ++i)
      for (int a = 0; a < 3; ++a) x[i][a] = mesh.points[std::size_t(3 * g[i] + a)];
    for (int a = 0; a < 3; ++a) {
      mn[a] = mx[a] = x[0][a];
      for (int i = 1; i < 8; ++i) {
        mn[a] = std::min(mn[a], x[i][a]);
        mx[a] = std::max(mx[a], x[i][a]);
      }
    }
    int lo[3], hi[3];
    if (!clipped_range(mn, mx, t0, t1, lo, hi)) return 0;
    // Most voxels of a hexahedron's box are often taken already (a grid through the mesh's
    // points puts each voxel in up to eight boxes): skip the set-up when all are.
    bool any_free = false;
    for (int z = lo[2]; z <= hi[2] && !any_free; ++z)
      for (int y = lo[1]; y <= hi[1] && !any_free; ++y)
        for (int xv = lo[0]; xv <= hi[0] && !any_free; ++xv)
          any_free = !inside[std::size_t(xv + std::int64_t(grid.dims.x) *
                                                   (y + std::int64_t(grid.dims.y) * z))];
    if (!any_free) return 0;
    double v[8] = {};
    if (!mesh.cell_values)
      for (int i = 0; i < 8; ++i) v[i] = mesh.values[std::size_t(g[i])];
    const float cell_value = mesh.cell_values ? mesh.values[std::size_t(c)] : 0.f;
    const Dims d = grid.dims;
    std::int64_t found = 0;
    // An affine hexahedron (a parallelepiped, as block-structured meshes have): ξ = A⁻¹ (p − x0)
    // exactly, no iteration.
    double a[3][3], size = 0;
    for (int k = 0; k < 3; ++k) {
      const int corner = k == 0 ? 1 : k == 1 ? 3 : 4;
      for (int r = 0; r < 3; ++r) a[r][k] = x[corner][r] - x[0][r];
    }
    for (int r = 0; r < 3; ++r) size = std::max(size, mx[r] - mn[r]);
    bool affine = true;
    for (int k : {2, 5, 6, 7})  // corners 0, 1, 3 and 4 define the map
      for (int r = 0; r < 3; ++r) {
        const double want = x[0][r] + a[r][0] * kCorner[k][0] + a[r][1] * kCorner[k][1] +
                            a[r][2] * kCorner[k][2];
        affine &= std::fabs(x[k][r] - want) <= 1e-12 * size;
      }
    double ai[3][3] = {};
    if (affine && !detail::inverse3(a, ai, kDegenerate * size * size * size)) return 0;
    double xi[3] = {0.5, 0.5, 0.5};
    std::int64_t iterations = 0, missed = 0;  // this row's, and those that found no voxel
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y) {
        if (iterations > 0) {  // the last row's Newton work
          work.add(iterations, missed);
          iterations = missed = 0;
          if (charge(work)) return found;
        }
        for (int xv = lo[0]; xv <= hi[0]; ++xv) {
          const std::size_t i = std::size_t(xv + std::int64_t(d.x) * (y + std::int64_t(d.y) * z));
          if (inside[i]) continue;
          const double p[3] = {voxel_coord(0, xv), voxel_coord(1, y), voxel_coord(2, z)};
          bool converged = affine;
          if (affine) {
            const double q[3] = {p[0] - x[0][0], p[1] - x[0][1], p[2] - x[0][2]};
            for (int r = 0; r < 3; ++r) xi[r] = ai[r][0] * q[0] + ai[r][1] * q[1] + ai[r][2] * q[2];
          } else {
            // Start from where the point sits in the cell's box (exact for a box).
            for (int r = 0; r < 3; ++r)
              xi[r] = mx[r] > mn[r] ? (p[r] - mn[r]) / (mx[r] - mn[r]) : 0.5;
          }
          int used = 0;
          for (int it = 0; it < kNewtonIterations && !converged; ++it) {
            ++used;
            // Residual x(ξ) − p and Jacobian ∂x/∂ξ of the trilinear map.
            double r[3] = {-p[0], -p[1], -p[2]}, jm[3][3] = {};
            for (int k = 0; k < 8; ++k) {
              const double f[3] = {kCorner[k][0] ? xi[0] : 1 - xi[0],
                                   kCorner[k][1] ? xi[1] : 1 - xi[1],
                                   kCorner[k][2] ? xi[2] : 1 - xi[2]};
              const double s[3] = {kCorner[k][0] ? 1.0 : -1.0, kCorner[k][1] ? 1.0 : -1.0,
                                   kCorner[k][2] ? 1.0 : -1.0};
              const double n = f[0] * f[1] * f[2];
              const double dn[3] = {s[0] * f[1] * f[2], f[0] * s[1] * f[2], f[0] * f[1] * s[2]};
              for (int a = 0; a < 3; ++a) {
                r[a] += n * x[k][a];
                for (int b = 0; b < 3; ++b) jm[a][b] += dn[b] * x[k][a];
              }
            }
            double ji[3][3];
            if (!detail::inverse3(jm, ji, 0)) break;
            const double dxi[3] = {ji[0][0] * r[0] + ji[0][1] * r[1] + ji[0][2] * r[2],
                                   ji[1][0] * r[0] + ji[1][1] * r[1] + ji[1][2] * r[2],
                                   ji[2][0] * r[0] + ji[2][1] * r[1] + ji[2][2] * r[2]};
            for (int a = 0; a < 3; ++a) xi[a] -= dxi[a];
            converged =
                std::fabs(dxi[0]) + std::fabs(dxi[1]) + std::fabs(dxi[2]) < kNewtonTolerance;
          }
          iterations += used;
          bool in = converged;
          for (int a = 0; a < 3; ++a)
            in &= xi[a] >= -kInsideTolerance && xi[a] <= 1 + kInsideTolerance;
          if (!in) {
            missed += used;
            continue;
          }
          double value = cell_value;
          if (!mesh.cell_values) {  // trilinear, as nested interpolations along ξ, η, ζ
            const double b0 = v[0] + xi[0] * (v[1] - v[0]), b1 = v[3] + xi[0] * (v[2] - v[3]);
            const double t0v = v[4] + xi[0] * (v[5] - v[4]), t1v = v[7] + xi[0] * (v[6] - v[7]);
            const double b = b0 + xi[1] * (b1 - b0), t = t0v + xi[1] * (t1v - t0v);
            value = b + xi[2] * (t - b);
          }
          values[i] = float(value);
          inside[i] = 1;
          ++found;
        }
      }
    work.add(iterations, missed);
    return found;
  }
};

}  // namespace

namespace {

// Bins every cell (and a cell's tetrahedra) into the tiles its box meets, in parallel over
// contiguous blocks of cells; read in block order, every tile's bins list its items in index
// order. Adds the tile tests, entries and visits to stats.
std::vector<std::vector<std::vector<Item>>> bin_items(Voxelizer& vx, const TetMesh& tets,
                                                      int threads, VoxelizeStats& stats) {
  const Mesh& mesh = vx.mesh;
  const std::int64_t nc = mesh.cell_count();
  const int blocks = int(std::min<std::int64_t>(
      std::max<std::int64_t>(nc, 1), std::int64_t(resolve_threads(threads)) * kBinBlocksPerWorker));
  std::vector<std::int64_t> tet_first(std::size_t(nc) + 1, 0);  // first tetrahedron of cell c
  for (std::size_t t = 0; t < tets.tets.size(); ++t) ++tet_first[std::size_t(tets.cell[t]) + 1];
  for (std::size_t c = 0; c < std::size_t(nc); ++c) tet_first[c + 1] += tet_first[c];
  std::vector<std::vector<std::vector<Item>>> block_bins(static_cast<std::size_t>(blocks));
  std::vector<VoxelizeStats> block_stats(static_cast<std::size_t>(blocks));
  parallel_for(blocks, 1, threads, [&](int, std::int64_t first, std::int64_t last) {
    for (std::int64_t b = first; b < last; ++b) {
      const std::int64_t c0 = nc * b / blocks, c1 = nc * (b + 1) / blocks;
      auto& bins = block_bins[std::size_t(b)];
      bins.resize(std::size_t(vx.tiles.count()));
      VoxelizeStats st;  // local: neighbouring blocks' stats share a cache line
      vx.bin_cells(c0, c1, tet_first[std::size_t(c0)], bins, st);
      block_stats[std::size_t(b)] = st;
    }
  });
  for (const VoxelizeStats& s : block_stats) {
    stats.tile_tests += s.tile_tests;
    stats.tile_entries += s.tile_entries;
    stats.visits += s.visits;
  }
  return block_bins;
}

// The binning's visits over the budget: too much overlap, or too fine a grid or --antialias.
FormatError binning_over_budget(const Voxelizer& vx, Dims d, int antialias) {
  const std::string passes =
      vx.visit_cost > 1 ? ", each visit counted " + std::to_string(vx.visit_cost) +
                              " times for --antialias " + std::to_string(antialias) +
                              "'s sub-samples"
                        : std::string();
  return FormatError(
      "the cells' bounding boxes cover more than " + std::to_string(vx.budget) +
      " voxels in all (" + std::to_string(kVisitsPerItem) + " per voxel of the " +
      to_string(d) + " grid and per cell's tetrahedron" + passes + "; stopped after " +
      std::to_string(vx.visits.load()) + "): cells overlap far more than a mesh that tiles "
      "space (many copies of large cells?), or the grid or --antialias asks for more work "
      "than the mesh can justify; refused rather than voxelized for hours");
}

// Newton's work over the budget: hexahedra far from parallelepipeds.
FormatError newton_over_budget(const Voxelizer& vx, Dims d, std::int64_t iterations) {
  return FormatError(
      "locating the voxels in the hexahedra took more than " + std::to_string(vx.budget) +
      " visits' work (" + std::to_string(kVisitsPerItem) + " per voxel of the " + to_string(d) +
      " grid and per cell, a Newton iteration counting " +
      std::to_string(kNewtonIterationVisits) + "; stopped after " + std::to_string(iterations) +
      " iterations): hexahedra far from parallelepipeds (stretched or twisted cells?) make "
      "Newton's method run long at every voxel of their boxes; refused rather than voxelized "
      "for minutes (--hex tetrahedra samples them through their tetrahedra)");
}

// The scan converter's accumulation buffer to voxels: inside when at least half the
// sub-samples are. Returns the voxels inside.
std::int64_t resolve_scan(const detail::ScanBuffers& acc, std::span<float> values,
                          std::span<std::uint8_t> inside) {
  std::int64_t count = 0;
  const int all = acc.k * acc.k * acc.k;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const int n = std::popcount(acc.taken[i]);
    if (2 * n < all) continue;
    values[i] = float(acc.sum[i] / n);
    inside[i] = 1;
    ++count;
  }
  return count;
}

// The two-buffer voxelizer's passes to voxels: inside when at least half of them hit. Returns
// the voxels inside.
std::int64_t resolve_passes(const detail::PassBuffers& passes, std::span<float> values,
                            std::span<std::uint8_t> inside) {
  std::int64_t count = 0;
  const int all = int(passes.offset.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const int n = std::popcount(passes.taken[i][0]) + std::popcount(passes.taken[i][1]);
    if (2 * n < all) continue;
    values[i] = float(passes.sum[i] / n);
    inside[i] = 1;
    ++count;
  }
  return count;
}

}  // namespace

VoxelizeStats voxelize(const Mesh& mesh, const VoxelGrid& grid, std::span<float> values,
                       std::span<std::uint8_t> inside, const SampleOptions& options) {
  const Dims d = grid.dims;
  assert(std::int64_t(values.size()) == d.count() && inside.size() == values.size());
  const bool two = options.kind == VoxelizerKind::two_buffer;
  assert(options.antialias >= 1 && options.antialias <= (two ? kMaxTwoBufferK : kMaxAntialias));
  const int threads = options.threads;
  const bool scan = options.kind == VoxelizerKind::scan;
  std::fill(values.begin(), values.end(), 0.f);
  std::fill(inside.begin(), inside.end(), std::uint8_t(0));
  const bool whole_hex = !scan && !two && options.hex == HexSampling::isoparametric;
  const bool all_hex = whole_hex && std::all_of(mesh.types.begin(), mesh.types.end(), is_hexahedral);
  const TetMesh tets = all_hex ? TetMesh{} : tetrahedralize(mesh, whole_hex);
  Voxelizer vx{mesh, tets, grid, values, inside, whole_hex, {}, {}, 0, 1, {}};
  if (scan)
    for (int a = 0; a < 3; ++a)
      vx.margin[std::size_t(a)] = (0.5 - 0.5 / options.antialias) * grid.spacing[std::size_t(a)];
  if (two)  // a pass's samples lie within half a voxel of the centres
    for (int a = 0; a < 3; ++a) vx.margin[std::size_t(a)] = 0.5 * grid.spacing[std::size_t(a)];
  vx.tiles = bar_tiles(d, resolve_threads(threads));
  VoxelizeStats stats;
  stats.tets = std::int64_t(tets.tets.size());
  for (CellType t : mesh.types) stats.hexahedra += whole_hex && is_hexahedral(t);
  vx.budget = std::max(kMinVisitBudget, kVisitsPerItem * (d.count() + stats.tets + stats.hexahedra));
  if (scan || two) vx.visit_cost = std::int64_t(options.antialias) * options.antialias *
                                   options.antialias;

  auto block_bins = bin_items(vx, tets, threads, stats);
  if (vx.over_budget()) throw binning_over_budget(vx, d, options.antialias);
  // Sample: tiles in parallel; in each, cells in index order, the first containing one wins.
  std::vector<std::int64_t> inside_count(std::size_t(vx.tiles.count()), 0);
  std::vector<std::int64_t> newton_count(std::size_t(vx.tiles.count()), 0);
  std::vector<std::int64_t> missed_count(std::size_t(vx.tiles.count()), 0);
  detail::ScanBuffers acc;
  if (scan) {
    acc.k = options.antialias;
    acc.taken.assign(values.size(), 0);
    acc.sum.assign(values.size(), 0.0);
  }
  detail::PassBuffers passes;
  if (two) {
    passes.k = options.antialias;
    passes.offset = detail::pass_offsets(options.antialias, options.jitter);
    passes.taken.assign(values.size(), {0, 0});
    passes.sum.assign(values.size(), 0.0);
  }
  parallel_for(vx.tiles.count(), 1, threads, [&](int, std::int64_t first, std::int64_t last) {
    for (std::int64_t ti = first; ti < last; ++ti) {
      const int tl[3] = {int(ti % vx.tiles.n[0]), int(ti / vx.tiles.n[0] % vx.tiles.n[1]),
                         int(ti / (std::int64_t(vx.tiles.n[0]) * vx.tiles.n[1]))};
      int t0[3], t1[3];
      for (int a = 0; a < 3; ++a) {
        t0[a] = tl[a] * vx.tiles.size[a];
        t1[a] = std::min(d[a] - 1, t0[a] + vx.tiles.size[a] - 1);
      }
      // The blocks' bins in block order: the tile's items in cell order, never merged.
      // Counted locally: neighbouring tiles' counters share a cache line across workers.
      std::int64_t found = 0;
      HexWork work;
      for (auto& block : block_bins) {
        for (Item item : block[std::size_t(ti)]) {
          if (vx.over_budget()) break;  // (Newton's work, in another tile or this one)
          found += scan        ? detail::scan_tet(tets, item, grid, t0, t1, acc)
                   : two       ? detail::two_buffer_tet(tets, item, grid, t0, t1, passes)
                   : item >= 0 ? vx.sample_tet(item, t0, t1)
                               : vx.sample_hex(-1 - item, t0, t1, work);
          vx.charge(work);
        }
        std::vector<Item>().swap(block[std::size_t(ti)]);
      }
      vx.charge(work, true);
      inside_count[std::size_t(ti)] = found;
      newton_count[std::size_t(ti)] = work.iterations;
      missed_count[std::size_t(ti)] = work.missed;
    }
  });
  for (std::int64_t n : newton_count) stats.newton_iterations += n;
  for (std::int64_t n : missed_count) stats.newton_missed += n;
  if (vx.over_budget()) throw newton_over_budget(vx, d, stats.newton_iterations);
  if (scan)
    stats.inside = resolve_scan(acc, values, inside);
  else if (two)
    stats.inside = resolve_passes(passes, values, inside);
  else
    for (std::int64_t c : inside_count) stats.inside += c;
  pad_outside(values, inside, d);
  return stats;
}

}  // namespace tsp

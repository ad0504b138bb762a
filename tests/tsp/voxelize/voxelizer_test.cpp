// The voxelizer against analytic answers: a linear field is reproduced at every inside voxel, a
// box of hexahedra covers every voxel, a hole's voxels (and only they) are outside, the
// separating-axis test agrees with clipping, padding takes the nearest inside value.
#include "tsp/voxelize/voxelizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tsp/core/error.h"
#include "tsp/voxelize/tet_box.h"
#include "tsp/voxelize/two_buffer.h"
#include "tsp/voxelize/voxelized_source.h"

namespace tsp {
namespace {

// An n³ grid of hexahedra over [0,1]³ with interior points jittered (cells stay convex), keeping
// the cells for which keep(centre) holds; values f(point).
template <typename Keep, typename F>
Mesh jittered_box(int n, double jitter, Keep keep, F f) {
  Mesh m;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  auto id = [&](int x, int y, int z) { return std::int64_t(x + (n + 1) * (y + (n + 1) * z)); };
  for (int z = 0; z <= n; ++z)
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x) {
        const int c[3] = {x, y, z};
        for (int a = 0; a < 3; ++a) {
          const bool inner = c[a] > 0 && c[a] < n;
          m.points.push_back((c[a] + (inner ? u(rng) : 0.0)) / n);
        }
      }
  m.offsets.push_back(0);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        if (!keep((x + 0.5) / n, (y + 0.5) / n, (z + 0.5) / n)) continue;
        for (auto p : {id(x, y, z), id(x + 1, y, z), id(x + 1, y + 1, z), id(x, y + 1, z),
                       id(x, y, z + 1), id(x + 1, y, z + 1), id(x + 1, y + 1, z + 1),
                       id(x, y + 1, z + 1)})
          m.connectivity.push_back(p);
        m.offsets.push_back(std::int64_t(m.connectivity.size()));
        m.types.push_back(CellType::hexahedron);
      }
  for (std::int64_t p = 0; p < m.point_count(); ++p)
    m.values.push_back(f(m.points[std::size_t(3 * p)], m.points[std::size_t(3 * p + 1)],
                         m.points[std::size_t(3 * p + 2)]));
  check_mesh(m, "test mesh");
  return m;
}

// Voxelizer A in both hexahedron modes, B and C without anti-aliasing: all sample voxel centres.
std::vector<SampleOptions> all_samplers() {
  SampleOptions iso, tets, scan, two;
  tets.hex = HexSampling::tetrahedra;
  scan.kind = VoxelizerKind::scan;
  two.kind = VoxelizerKind::two_buffer;
  iso.threads = tets.threads = scan.threads = two.threads = 2;
  return {iso, tets, scan, two};
}

VoxelGrid unit_grid(int n) {
  VoxelGrid g;
  g.dims = Dims{n, n, n};
  g.spacing = {1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1)};
  return g;
}

TEST(Voxelizer, LinearFieldIsExactAtEveryVoxelAndTheBoxIsCovered) {
  auto f = [](double x, double y, double z) { return float(1 + 2 * x - 3 * y + 0.5 * z); };
  const Mesh m = jittered_box(6, 0.2, [](double, double, double) { return true; }, f);
  const VoxelGrid g = unit_grid(23);
  std::vector<float> v(std::size_t(g.dims.count()));
  std::vector<std::uint8_t> in(v.size());
  for (const SampleOptions& so : all_samplers()) {
  const VoxelizeStats st = voxelize(m, g, v, in, so);
  EXPECT_EQ(st.inside, g.dims.count());  // no gap anywhere, faces and boundary included
  for (int z = 0; z < 23; ++z)
    for (int y = 0; y < 23; ++y)
      for (int x = 0; x < 23; ++x) {
        const std::size_t i = std::size_t(x + 23 * (y + 23 * z));
        ASSERT_TRUE(in[i]);
        EXPECT_NEAR(v[i], f(x / 22.0, y / 22.0, z / 22.0), 2e-6) << x << "," << y << "," << z;
      }
  }
}

TEST(Voxelizer, FirstCellInIndexOrderWinsWhateverTheWorkers) {
  // Two overlapping boxes of hexahedra in one mesh, A ([0, 1]³, value 1) before B ([0.5, 1.5]³,
  // value 2): the overlap takes A's value. Tiles follow the worker count; the picture must not.
  const auto one = [](double, double, double) { return 1.f; };
  Mesh m = jittered_box(6, 0.2, [](double, double, double) { return true; }, one);
  const Mesh b = jittered_box(5, 0.2, [](double, double, double) { return true; }, one);
  const std::int64_t base = m.point_count();
  for (std::size_t i = 0; i < b.points.size(); ++i) m.points.push_back(b.points[i] + 0.5);
  for (std::int64_t p : b.connectivity) m.connectivity.push_back(p + base);
  for (std::size_t c = 1; c < b.offsets.size(); ++c)
    m.offsets.push_back(m.offsets.back() + b.offsets[c] - b.offsets[c - 1]);
  m.types.insert(m.types.end(), b.types.begin(), b.types.end());
  m.values.insert(m.values.end(), b.values.size(), 2.f);
  check_mesh(m, "two boxes");
  VoxelGrid g;
  g.dims = Dims{45, 45, 45};  // several tiles, no voxel centre on a box's face
  g.origin = {0.01, 0.01, 0.01};
  g.spacing = {1.0 / 30, 1.0 / 30, 1.0 / 30};
  std::vector<float> first_v;
  for (SampleOptions so : all_samplers())
    for (int threads : {1, 2, 3}) {
      so.threads = threads;
      std::vector<float> v(std::size_t(g.dims.count()));
      std::vector<std::uint8_t> in(v.size());
      voxelize(m, g, v, in, so);
      for (int z = 0; z < 45; ++z)
        for (int y = 0; y < 45; ++y)
          for (int x = 0; x < 45; ++x) {
            const double p[3] = {0.01 + x / 30.0, 0.01 + y / 30.0, 0.01 + z / 30.0};
            bool in_a = true, in_b = true;
            for (double c : p) {
              in_a &= c < 1;
              in_b &= c > 0.5;
            }
            const std::size_t i = std::size_t(x + 45 * (y + 45 * z));
            ASSERT_EQ(in[i], in_a || in_b) << x << "," << y << "," << z;
            if (in[i]) {
              ASSERT_EQ(v[i], in_a ? 1.f : 2.f) << x << "," << y << "," << z;
            }
          }
      if (first_v.empty()) first_v = v;
      if (so.kind == VoxelizerKind::locate) {
        EXPECT_EQ(v, first_v) << "padding too";
      }
    }
}

TEST(Voxelizer, HoleVoxelsAreOutsideAndPaddedFromTheirNeighbours) {
  // Cells whose centre lies within 0.3 of the axis x = y = 0.5 are removed: on a grid of cell
  // centres, exactly those voxels are outside.
  const int n = 10;
  auto hole = [](double x, double y, double) { return std::hypot(x - 0.5, y - 0.5) < 0.3; };
  const Mesh m = jittered_box(n, 0.0, [&](double x, double y, double z) { return !hole(x, y, z); },
                              [](double x, double, double) { return float(x); });
  VoxelGrid g;
  g.dims = Dims{n, n, n};
  g.origin = {0.5 / n, 0.5 / n, 0.5 / n};
  g.spacing = {1.0 / n, 1.0 / n, 1.0 / n};
  std::vector<float> v(std::size_t(g.dims.count()));
  std::vector<std::uint8_t> in(v.size());
  for (const SampleOptions& so : all_samplers()) {
  voxelize(m, g, v, in, so);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const std::size_t i = std::size_t(x + n * (y + n * z));
        const double cx = (x + 0.5) / n, cy = (y + 0.5) / n;
        EXPECT_EQ(in[i], hole(cx, cy, 0) ? 0 : 1) << x << "," << y;
        // Padding copies an inside value from the nearest ring, so it stays in [0, 1].
        EXPECT_GE(v[i], 0.f);
        EXPECT_LE(v[i], 1.f);
      }
  }
}

TEST(Voxelizer, ScanAntialiasingAveragesTheCoveredSubsamples) {
  // One hexahedron [0, 0.55] x [0, 1] x [0, 1], f = x, voxel centres every 0.25 from 0. The
  // voxel at x = 0.5 spans [0.375, 0.625]: of its 4 sub-samples per axis (x = 0.40625 …
  // 0.59375) the mesh covers 3, so with K = 4 it is inside (48 of 64) and holds their mean x;
  // the voxel at 0.75 is outside. Without anti-aliasing both are located at their centre.
  Mesh m;
  m.points = {0, 0, 0, 0.55, 0, 0, 0.55, 1, 0, 0, 1, 0, 0, 0, 1, 0.55, 0, 1, 0.55, 1, 1, 0, 1, 1};
  m.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  m.offsets = {0, 8};
  m.types = {CellType::hexahedron};
  for (int p = 0; p < 8; ++p) m.values.push_back(float(m.points[std::size_t(3 * p)]));
  VoxelGrid g;
  g.dims = Dims{4, 5, 5};
  g.spacing = {0.25, 0.25, 0.25};
  std::vector<float> v(std::size_t(g.dims.count()));
  std::vector<std::uint8_t> in(v.size());
  SampleOptions so;
  so.kind = VoxelizerKind::scan;
  so.antialias = 4;
  voxelize(m, g, v, in, so);
  const std::size_t mid = std::size_t(0 + 4 * (2 + 5 * 2));  // (x, y, z) = (0, 2, 2)
  EXPECT_TRUE(in[mid + 2]);
  EXPECT_NEAR(v[mid + 2], (0.40625 + 0.46875 + 0.53125) / 3, 1e-6);
  EXPECT_FALSE(in[mid + 3]);
  EXPECT_NEAR(v[mid + 1], 0.25, 1e-6);  // a whole voxel: the mean of its sub-samples, its centre
  so.antialias = 1;
  voxelize(m, g, v, in, so);
  EXPECT_NEAR(v[mid + 2], 0.5, 1e-6);
  EXPECT_FALSE(in[mid + 3]);
}

TEST(Voxelizer, ScanSubsamplesReachCellsBetweenVoxelCentres) {
  // Cells (1/20) much smaller than voxels (1/6): many hold sub-samples but no voxel centre. A
  // fully covered voxel's mean over its symmetric sub-samples of a linear field is its value at
  // the centre; every voxel off the box's edges is at least half covered.
  auto f = [](double x, double y, double z) { return float(1 + 2 * x - 3 * y + 0.5 * z); };
  const Mesh m = jittered_box(20, 0.2, [](double, double, double) { return true; }, f);
  const VoxelGrid g = unit_grid(7);
  std::vector<float> v(std::size_t(g.dims.count()));
  std::vector<std::uint8_t> in(v.size());
  for (int k = 2; k <= kMaxAntialias; ++k) {
    SampleOptions so;
    so.kind = VoxelizerKind::scan;
    so.antialias = k;
    voxelize(m, g, v, in, so);
    for (int z = 0; z < 7; ++z)
      for (int y = 0; y < 7; ++y)
        for (int x = 0; x < 7; ++x) {
          const int faces = (x == 0 || x == 6) + (y == 0 || y == 6) + (z == 0 || z == 6);
          const std::size_t i = std::size_t(x + 7 * (y + 7 * z));
          EXPECT_EQ(in[i], faces <= 1 ? 1 : 0) << k << ": " << x << "," << y << "," << z;
          if (faces == 0) {
            EXPECT_NEAR(v[i], f(x / 6.0, y / 6.0, z / 6.0), 1e-5) << k;
          }
        }
  }
}

// Voxelizer C (two buffers) samples the lattice voxelizer B does: at every K without jitter,
// the same voxels inside and the same values, on a mesh with a hole (cells of 1/9, voxels of
// 1/10: sub-samples on shared faces and near the hole's walls).
TEST(Voxelizer, TwoBufferTakesTheSamplesScanTakesAtEveryK) {
  auto f = [](double x, double y, double z) { return float(2 * x * x - y + 3 * z); };
  const Mesh m = jittered_box(9, 0.2, [](double x, double y, double) {
    return (x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5) > 0.04;
  }, f);
  const VoxelGrid g = unit_grid(11);
  std::vector<float> vs(std::size_t(g.dims.count())), vt(vs.size());
  std::vector<std::uint8_t> is(vs.size()), it(vs.size());
  for (int k = 1; k <= kMaxAntialias; ++k) {
    SampleOptions scan, two;
    scan.kind = VoxelizerKind::scan;
    two.kind = VoxelizerKind::two_buffer;
    scan.antialias = two.antialias = k;
    const VoxelizeStats a = voxelize(m, g, vs, is, scan);
    const VoxelizeStats b = voxelize(m, g, vt, it, two);
    EXPECT_EQ(a.inside, b.inside) << k;
    EXPECT_GT(b.inside, 0);
    EXPECT_LT(b.inside, g.dims.count());  // the hole
    for (std::size_t i = 0; i < vs.size(); ++i) {
      EXPECT_EQ(is[i], it[i]) << "K " << k << " voxel " << i;
      EXPECT_NEAR(vs[i], vt[i], 1e-5) << "K " << k << " voxel " << i;
    }
  }
}

// K = 5 and the jittered pattern: a fully covered voxel of a linear field holds the field at its
// centre moved by the passes' mean offset (0 without jitter), and a voxel on the box's faces,
// edges or corners is inside exactly when at least half its passes' samples fall in the box.
TEST(Voxelizer, TwoBufferPassesAverageALinearFieldAtTheirMeanOffset) {
  auto f = [](double x, double y, double z) { return 1 + 2 * x - 3 * y + 0.5 * z; };
  const Mesh m = jittered_box(20, 0.2, [](double, double, double) { return true; },
                              [&](double x, double y, double z) { return float(f(x, y, z)); });
  const VoxelGrid g = unit_grid(7);
  std::vector<float> v(std::size_t(g.dims.count()));
  std::vector<std::uint8_t> in(v.size());
  for (bool jitter : {false, true}) {
    SampleOptions so;
    so.kind = VoxelizerKind::two_buffer;
    so.antialias = kMaxTwoBufferK;
    so.jitter = jitter;
    voxelize(m, g, v, in, so);
    std::array<double, 3> mean{0, 0, 0};
    const auto offsets = detail::pass_offsets(kMaxTwoBufferK, jitter);
    ASSERT_EQ(offsets.size(), 125u);
    for (const auto& o : offsets)
      for (int a = 0; a < 3; ++a) mean[std::size_t(a)] += o[std::size_t(a)] / 125;
    for (int z = 0; z < 7; ++z)
      for (int y = 0; y < 7; ++y)
        for (int x = 0; x < 7; ++x) {
          const int faces = (x == 0 || x == 6) + (y == 0 || y == 6) + (z == 0 || z == 6);
          const std::size_t i = std::size_t(x + 7 * (y + 7 * z));
          if (faces == 0) {
            EXPECT_TRUE(in[i]);
            EXPECT_NEAR(v[i], f((x + mean[0]) / 6, (y + mean[1]) / 6, (z + mean[2]) / 6), 1e-5)
                << jitter;
          }
          // A voxel on the box's faces holds the passes whose sample falls inside the box:
          // at least half of them, or it is outside.
          int hits = 0;
          const int c[3] = {x, y, z};
          for (const auto& o : offsets) {
            bool hit = true;
            for (int a = 0; a < 3; ++a) {
              if (c[a] == 0) hit &= o[std::size_t(a)] >= 0;
              if (c[a] == 6) hit &= o[std::size_t(a)] <= 0;
            }
            hits += hit;
          }
          EXPECT_EQ(bool(in[i]), 2 * hits >= 125) << jitter << ": " << x << "," << y << "," << z;
        }
  }
}

// One tetrahedron whose vertices lie a billion units away, holding the whole grid: every
// voxelizer takes every voxel and the linear field (x) at its centre — the scan converters clamp
// to the tile before converting coordinates to integers.
TEST(Voxelizer, AHugeTetrahedronAroundTheGridIsSampledExactly) {
  Mesh m;
  m.points = {-1e9, -1e9, -1e9, 4e9, -1e9, -1e9, -1e9, 4e9, -1e9, -1e9, -1e9, 4e9};
  m.connectivity = {0, 1, 2, 3};
  m.offsets = {0, 4};
  m.types = {CellType::tetra};
  for (int p = 0; p < 4; ++p) m.values.push_back(float(m.points[std::size_t(3 * p)]));
  check_mesh(m, "huge tet");
  const VoxelGrid g = unit_grid(9);
  std::vector<float> v(std::size_t(g.dims.count()));
  std::vector<std::uint8_t> in(v.size());
  for (const SampleOptions& so : all_samplers()) {
    const VoxelizeStats st = voxelize(m, g, v, in, so);
    EXPECT_EQ(st.inside, g.dims.count()) << int(so.kind);
    for (int z = 0; z < 9; ++z)
      for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 9; ++x)
          EXPECT_NEAR(v[std::size_t(x + 9 * (y + 9 * z))], x / 8.0, 1e-3) << int(so.kind);
  }
}

TEST(Voxelizer, PassOffsetsAreSubCellCentresOrJitteredInsideThem) {
  EXPECT_EQ(detail::pass_offsets(1, false), (std::vector<std::array<double, 3>>{{0, 0, 0}}));
  for (int k = 1; k <= kMaxTwoBufferK; ++k) {
    const auto plain = detail::pass_offsets(k, false), jittered = detail::pass_offsets(k, true);
    ASSERT_EQ(plain.size(), std::size_t(k * k * k));
    ASSERT_EQ(jittered, detail::pass_offsets(k, true));  // a fixed pattern
    bool moved = false;
    for (std::size_t p = 0; p < plain.size(); ++p)
      for (int a = 0; a < 3; ++a) {
        const double d = jittered[p][std::size_t(a)] - plain[p][std::size_t(a)];
        EXPECT_LE(std::abs(d), detail::kJitterShare / k + 1e-12);
        moved |= std::abs(d) > 1e-6;
        EXPECT_GT(jittered[p][std::size_t(a)], -0.5);
        EXPECT_LT(jittered[p][std::size_t(a)], 0.5);
      }
    EXPECT_TRUE(moved) << k;
    // The K passes of a sub-pixel share its x and y (they share the two buffers).
    for (std::size_t p = 0; p < plain.size(); ++p)
      for (int a = 0; a < 2; ++a)
        EXPECT_EQ(jittered[p][std::size_t(a)], jittered[p % std::size_t(k * k)][std::size_t(a)]);
  }
}

TEST(Voxelizer, PadOutsideTakesTheNearestInsideValue) {
  const Dims d{5, 1, 1};
  std::vector<float> v = {0, 0, 7, 0, 9};
  const std::vector<std::uint8_t> in = {0, 0, 1, 0, 1};
  pad_outside(v, in, d);
  EXPECT_EQ(v, (std::vector<float>{7, 7, 7, 7, 9}));
}

// Clipping reference: the tet and the box overlap iff a tet face clipped to the box keeps area
// or the box lies inside the tet.
bool overlap_by_clipping(const std::array<Vec3, 4>& t, const Aabb& b) {
  const int faces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (const auto& f : faces) {
    std::vector<Vec3> poly = {t[std::size_t(f[0])], t[std::size_t(f[1])], t[std::size_t(f[2])]};
    for (int a = 0; a < 3 && !poly.empty(); ++a)
      for (int side = 0; side < 2 && !poly.empty(); ++side) {
        std::vector<Vec3> out;
        auto inside = [&](const Vec3& p) { return side ? p[a] <= b.hi[a] : p[a] >= b.lo[a]; };
        const double plane = side ? b.hi[a] : b.lo[a];
        for (std::size_t i = 0; i < poly.size(); ++i) {
          const Vec3 &p = poly[i], &q = poly[(i + 1) % poly.size()];
          if (inside(p)) out.push_back(p);
          if (inside(p) != inside(q)) {
            const double s = (plane - p[a]) / (q[a] - p[a]);
            out.push_back({p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1]), p[2] + s * (q[2] - p[2])});
          }
        }
        poly = out;
      }
    if (!poly.empty()) return true;
  }
  // Box corner inside the tet (barycentric signs agree with the fourth vertex for each face).
  auto side = [](const Vec3& a, const Vec3& b2, const Vec3& c, const Vec3& p) {
    const double u[3] = {b2[0] - a[0], b2[1] - a[1], b2[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    return n[0] * (p[0] - a[0]) + n[1] * (p[1] - a[1]) + n[2] * (p[2] - a[2]);
  };
  const Vec3 corner = {b.lo[0], b.lo[1], b.lo[2]};
  for (const auto& f : faces) {
    int o = 6 - f[0] - f[1] - f[2];
    const auto& A = t[std::size_t(f[0])];
    const auto& B = t[std::size_t(f[1])];
    const auto& C = t[std::size_t(f[2])];
    if (side(A, B, C, corner) * side(A, B, C, t[std::size_t(o)]) < 0) return false;
  }
  return true;
}

TEST(TetBox, SeparatingAxisTestAgreesWithClipping) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1), s(0.05, 0.8);
  int overlaps = 0, disjoint = 0;
  for (int i = 0; i < 20000; ++i) {
    std::array<Vec3, 4> t;
    for (auto& p : t) p = {u(rng), u(rng), u(rng)};
    Aabb b;
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = u(rng) * 0.8;
      b.hi[a] = b.lo[a] + s(rng);
    }
    const bool want = overlap_by_clipping(t, b);
    ASSERT_EQ(tet_box_overlap(t, b), want) << "pair " << i;
    (want ? overlaps : disjoint)++;
  }
  EXPECT_GT(overlaps, 1000);
  EXPECT_GT(disjoint, 1000);
}

TEST(VoxelGridRule, ResolutionVoxelSizeAndMedianCellSize) {
  Aabb b;
  b.hi = {2, 1, 0.5};
  VoxelizeOptions o;
  o.resolution = 41;
  VoxelGrid g = choose_grid(b, 0, o);
  EXPECT_EQ(g.dims, (Dims{41, 21, 11}));
  EXPECT_DOUBLE_EQ(g.spacing[0], 0.05);
  o = {};
  o.voxel_size = 0.5;
  EXPECT_EQ(choose_grid(b, 0, o).dims, (Dims{5, 3, 2}));
  o = {};
  EXPECT_EQ(choose_grid(b, 0.1, o).dims.x, 21);                       // one sample per cell
  EXPECT_EQ(choose_grid(b, 1e-4, o).dims.x, kMaxDefaultResolution);   // held to the maximum
  EXPECT_EQ(choose_grid(b, 10, o).dims.x, kMinDefaultResolution);     // and the minimum
  o.resolution = 10;
  o.voxel_size = 1;
  EXPECT_THROW(choose_grid(b, 0, o), UsageError);
  o = {};
  o.voxel_size = 1e-6;
  EXPECT_THROW(choose_grid(b, 0, o), UsageError);  // beyond kMaxVoxelizedSamples
  const Mesh m = jittered_box(4, 0, [](double, double, double) { return true; },
                              [](double, double, double) { return 0.f; });
  EXPECT_NEAR(median_cell_size(tetrahedralize(m)), 0.25, 1e-12);
}

// The work bound (issue 28): whole hexahedra visit exactly the voxels of their boxes — one
// unit-cube hexahedron on a 9³ grid, 9³ visits per copy — and copies beyond the budget,
// kVisitsPerItem × (voxels + hexahedra) but at least kMinVisitBudget, are refused before any
// voxel is sampled.
TEST(Voxelizer, CellsOverlappingFarBeyondTheBudgetAreRefused) {
  const Mesh one = jittered_box(1, 0, [](double, double, double) { return true; },
                                [](double, double, double) { return 1.f; });
  auto copies = [&](std::int64_t n) {
    Mesh m = one;
    m.connectivity.clear();
    m.offsets = {0};
    m.types.clear();
    for (std::int64_t c = 0; c < n; ++c) {
      m.connectivity.insert(m.connectivity.end(), one.connectivity.begin(), one.connectivity.end());
      m.offsets.push_back(std::int64_t(m.connectivity.size()));
      m.types.push_back(CellType::hexahedron);
    }
    return m;
  };
  const VoxelGrid g = unit_grid(9);
  std::vector<float> v(std::size_t(g.dims.count()));
  std::vector<std::uint8_t> in(v.size());
  SampleOptions so;
  so.threads = 2;
  const VoxelizeStats st = voxelize(copies(3), g, v, in, so);
  EXPECT_EQ(st.visits, 3 * 729);
  EXPECT_EQ(st.inside, 729);
  // kMinVisitBudget / 729 copies fit (the budget's other term is smaller here); one more is
  // refused.
  const std::int64_t fit = kMinVisitBudget / 729;
  ASSERT_LT(kVisitsPerItem * (729 + fit + 1), kMinVisitBudget);
  EXPECT_THROW(voxelize(copies(fit + 1), g, v, in, so), FormatError);
}

}  // namespace
}  // namespace tsp

// The LOD level filter against independent computations: a direct 3-D weighted sum, exactness on
// linear fields at every level, agreement of neighbours on shared faces, and the residual.
#include "tsp/build/level_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tsp/tree/octree.h"

namespace tsp {
namespace {

std::vector<float> field(Dims d, auto f) {
  std::vector<float> v(std::size_t(d.count()));
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) v[std::size_t(x + d.x * (y + std::int64_t(d.y) * z))] = f(x, y, z);
  return v;
}

// The filter written out as one 3-D sum with the documented weights (½ at the window's ends).
double brute_force(const std::vector<float>& v, Dims d, std::array<int, 3> p, std::array<int, 3> f) {
  std::array<int, 3> r{};
  for (int a = 0; a < 3; ++a) {
    p[a] = std::min(p[a], d[a] - 1);
    r[a] = std::min({f[a] / 2, p[a], d[a] - 1 - p[a]});
  }
  auto w = [&](int a, int q) { return r[a] > 0 && std::abs(q - p[a]) == r[a] ? 0.5 : 1.0; };
  double sum = 0, wsum = 0;
  for (int z = p[2] - r[2]; z <= p[2] + r[2]; ++z)
    for (int y = p[1] - r[1]; y <= p[1] + r[1]; ++y)
      for (int x = p[0] - r[0]; x <= p[0] + r[0]; ++x) {
        const double k = w(0, x) * w(1, y) * w(2, z);
        sum += k * v[std::size_t(x + d.x * (y + std::int64_t(d.y) * z))];
        wsum += k;
      }
  return sum / wsum;
}

TEST(LevelFilter, MatchesTheDirectWeightedSumForEveryLevelBrick) {
  const Dims d{37, 30, 23};
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  const auto v = field(d, [&](int, int, int) { return u(rng); });
  const Octree o(d, 8);
  ASSERT_GT(o.level_brick_count(), 3);
  std::vector<float> out;
  for (int i = o.brick_count(); i < o.stored_brick_count(); ++i) {
    const BrickLattice l = o.lattice(i);
    filter_level(v, d, l, std::nullopt, out);
    ASSERT_EQ(std::int64_t(out.size()), l.count());
    for (int z = 0; z < l.samples[2]; ++z)
      for (int y = 0; y < l.samples[1]; ++y)
        for (int x = 0; x < l.samples[0]; ++x) {
          const std::array<int, 3> p{l.origin[0] + x * l.factor[0], l.origin[1] + y * l.factor[1],
                                     l.origin[2] + z * l.factor[2]};
          ASSERT_NEAR(out[std::size_t(x + l.samples[0] * (y + l.samples[1] * z))],
                      brute_force(v, d, p, l.factor), 1e-5)
              << "level brick " << i << " sample " << x << "," << y << "," << z;
        }
  }
}

TEST(LevelFilter, ReproducesALinearFieldAtEveryLevelWithZeroResidual) {
  const Dims d{65, 40, 33};
  auto lin = [](double x, double y, double z) { return 0.25 + 0.01 * x - 0.02 * y + 0.005 * z; };
  const auto v = field(d, [&](int x, int y, int z) { return float(lin(x, y, z)); });
  const Octree o(d, 16);
  std::vector<float> out;
  for (int i = o.brick_count(); i < o.stored_brick_count(); ++i) {
    const BrickLattice l = o.lattice(i);
    filter_level(v, d, l, std::nullopt, out);
    for (int z = 0; z < l.samples[2]; ++z)
      for (int y = 0; y < l.samples[1]; ++y)
        for (int x = 0; x < l.samples[0]; ++x) {
          const double px = std::min(l.origin[0] + x * l.factor[0], d.x - 1);
          const double py = std::min(l.origin[1] + y * l.factor[1], d.y - 1);
          const double pz = std::min(l.origin[2] + z * l.factor[2], d.z - 1);
          ASSERT_NEAR(out[std::size_t(x + l.samples[0] * (y + l.samples[1] * z))],
                      lin(px, py, pz), 1e-5);
        }
    // Only the clamped last samples (beyond the grid) may deviate from the line.
    const Box own = o.node(o.stored_brick_node(i)).box;
    Box inner = own;
    for (int a = 0; a < 3; ++a)
      inner.hi[a] = std::min(own.hi[a], l.origin[a] + (l.samples[a] - 1) * l.factor[a] <= d[a] - 1
                                            ? own.hi[a]
                                            : l.origin[a] + (l.samples[a] - 2) * l.factor[a] + 1);
    EXPECT_LT(level_residual(v, d, l, inner, out, std::nullopt), 1e-5) << "level brick " << i;
  }
}

TEST(LevelFilter, NeighboursAtOneLevelAgreeOnTheirSharedFace) {
  const Dims d{65, 65, 65};
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0, 1);
  const auto v = field(d, [&](int, int, int) { return u(rng); });
  const Octree o(d, 16);  // 5 bricks per axis
  std::vector<float> a_out, b_out;
  int pairs = 0;
  for (int i = o.brick_count(); i < o.stored_brick_count(); ++i)
    for (int j = o.brick_count(); j < o.stored_brick_count(); ++j) {
      const BrickLattice a = o.lattice(i), b = o.lattice(j);
      if (a.factor != b.factor || i == j) continue;
      // b's lower x face is a's upper sample layer, and they overlap in y and z.
      const int face = a.origin[0] + (a.samples[0] - 1) * a.factor[0];
      if (b.origin[0] != face || a.origin[1] != b.origin[1] || a.origin[2] != b.origin[2] ||
          face > d.x - 1)
        continue;
      filter_level(v, d, a, std::nullopt, a_out);
      filter_level(v, d, b, std::nullopt, b_out);
      for (int z = 0; z < std::min(a.samples[2], b.samples[2]); ++z)
        for (int y = 0; y < std::min(a.samples[1], b.samples[1]); ++y)
          EXPECT_EQ(a_out[std::size_t(a.samples[0] - 1 + a.samples[0] * (y + a.samples[1] * z))],
                    b_out[std::size_t(b.samples[0] * (y + b.samples[1] * z))]);
      ++pairs;
    }
  EXPECT_GT(pairs, 0);
}

TEST(LevelFilter, ClampsIntoTheRangeAndLeavesNonFiniteSamplesOut) {
  const Dims d{17, 17, 17};
  auto v = field(d, [](int x, int, int) { return x < 8 ? 2.f : 0.5f; });
  v[3] = std::nanf("");  // (3, 0, 0) and (5, 0, 0): inside the window of the sample at x = 4
  v[5] = INFINITY;
  const Octree o(d, 8);
  const BrickLattice root = o.lattice(o.node_brick(0));
  std::vector<float> out;
  filter_level(v, d, root, ValueRange{0, 1}, out);
  for (float x : out) {
    ASSERT_TRUE(std::isfinite(x));
    EXPECT_GE(x, 0.f);
    EXPECT_LE(x, 1.f);
  }
  // The sample at (4, 0, 0) averages its finite neighbours (2 clamped to 1) without the NaN and
  // the infinity.
  ASSERT_EQ(root.factor[0], 4);
  EXPECT_FLOAT_EQ(out[1], 1.f);
  // A window holding no finite sample gives NaN (the builder's sanitizer maps it like any NaN).
  v[0] = std::nanf("");
  filter_level(v, d, root, ValueRange{0, 1}, out);
  EXPECT_TRUE(std::isnan(out[0]));
}

}  // namespace
}  // namespace tsp

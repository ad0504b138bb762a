// LevelStream against the whole-volume filter and residual: fed the planes in slabs of any
// height, dropping every plane below needs_from() after each feed, it gives the same bits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <random>

#include "tsp/build/level_filter.h"
#include "tsp/tree/octree.h"

namespace tsp {
namespace {

TEST(LevelStream, GivesTheWholeVolumesBitsFromSlabsOfAnyHeightHoldingOnlyWhatItNeeds) {
  const Dims d{37, 30, 45};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<float> v(std::size_t(d.count()));
  for (float& x : v) x = u(rng);
  v[100] = std::nanf("");  // non-finite voxels are left out in both
  v[5000] = INFINITY;
  const std::int64_t plane = std::int64_t(d.x) * d.y;
  const Octree o(d, 8);
  ASSERT_GT(o.level_brick_count(), 5);
  const std::optional<ValueRange> clamp = ValueRange{-0.9, 0.8};
  for (int i = o.brick_count(); i < o.stored_brick_count(); ++i) {
    const BrickLattice l = o.lattice(i);
    const Box own = o.node(o.stored_brick_node(i)).box;
    std::vector<float> want;
    filter_level(v, d, l, clamp, want);
    const double want_residual = level_residual(v, d, l, own, want, clamp);
    LevelStream s(d, l, own, clamp);
    for (int h : {1, 3, 8, 45}) {
      s.restart();
      std::map<int, std::vector<float>> held;  // plane copies: a dropped plane cannot be read
      for (int z0 = 0; z0 < d.z; z0 += h) {
        const int z1 = std::min(d.z, z0 + h);
        for (int z = z0; z < z1; ++z)
          held[z].assign(v.begin() + z * plane, v.begin() + (z + 1) * plane);
        s.feed([&](int z) { return held.at(z).data(); }, z1);
        std::erase_if(held, [&](const auto& p) { return p.first < s.needs_from(); });
        // A stream never holds more planes than its window and residual need.
        EXPECT_LE(int(held.size()), h + 2 * l.factor[2] + 2) << "brick " << i << " h " << h;
      }
      ASSERT_TRUE(s.done()) << "brick " << i << " h " << h;
      ASSERT_EQ(s.samples().size(), want.size());
      EXPECT_EQ(std::memcmp(s.samples().data(), want.data(), want.size() * sizeof(float)), 0)
          << "brick " << i << " h " << h;
      EXPECT_EQ(s.residual(), want_residual) << "brick " << i << " h " << h;
      s.release();
    }
  }
}

}  // namespace
}  // namespace tsp

// The LOD cut: it covers the volume exactly once after any sequence of splits and merges, and
// the fixed-level cuts hold the levels they promise.
#include "tsp/lod/lod_cut.h"

#include <gtest/gtest.h>

#include <random>

namespace tsp {
namespace {

TEST(LodCut, CoversTheVolumeOnceAfterRandomSplitsAndMerges) {
  for (Dims d : {Dims{65, 65, 65}, Dims{100, 40, 14}, Dims{129, 70, 33}}) {
    const Octree o(d, 8);
    std::mt19937 rng(11);
    LodCut cut(o);
    ASSERT_TRUE(cut.covers_once());
    int splits = 0, merges = 0;
    for (int k = 0; k < 2000; ++k) {
      // A random cut node is split, or a random parent of one merged (when it can be).
      const auto nodes = cut.nodes();
      const int id = nodes[std::uniform_int_distribution<std::size_t>(0, nodes.size() - 1)(rng)];
      if (rng() % 2 == 0 && cut.can_split(id)) {
        cut.split(id);
        ++splits;
      } else if (const int p = o.node(id).parent; p >= 0 && cut.can_merge(p)) {
        cut.merge(p);
        ++merges;
      }
      ASSERT_TRUE(cut.covers_once()) << "after " << k << " operations";
      ASSERT_EQ(int(cut.nodes().size()), cut.size());
    }
    EXPECT_GT(splits, 20);
    EXPECT_GT(merges, 5);
  }
}

TEST(LodCut, FixedLevelsHoldOnlyNodesAtOrBelowTheirLevel) {
  const Octree o({129, 129, 129}, 16);  // 9 bricks per axis: levels 0 … 4
  ASSERT_EQ(o.max_lod_level(), 4);
  for (int k = 0; k <= o.max_lod_level() + 1; ++k) {
    const LodCut cut = LodCut::at_level(o, k);
    EXPECT_TRUE(cut.covers_once());
    const auto per_level = cut.nodes_per_level();
    int total = 0;
    for (int level = 0; level < int(per_level.size()); ++level) {
      total += per_level[std::size_t(level)];
      if (level > k) {
        EXPECT_EQ(per_level[std::size_t(level)], 0) << "cut at level " << k;
      }
    }
    EXPECT_EQ(total, cut.size());
    for (int id : cut.nodes()) {
      EXPECT_LE(o.lod_level(id), k);
      const int p = o.node(id).parent;
      if (p >= 0) {
        EXPECT_GT(o.lod_level(p), k);  // the coarsest such nodes
      }
    }
  }
  EXPECT_EQ(LodCut::at_level(o, 0).size(), o.brick_count());
  EXPECT_EQ(LodCut::at_level(o, o.max_lod_level()).size(), 1);
}

TEST(LodCut, LevelsGrowTowardsTheRootAndThinAxesKeepFullResolution) {
  const Octree o({200, 180, 14}, 16);  // one brick thick in z
  for (int id = 1; id < o.size(); ++id)
    EXPECT_LT(o.lod_level(id), o.lod_level(o.node(id).parent));
  for (int id = 0; id < o.size(); ++id) {
    const auto f = o.lod_factor(id);
    EXPECT_EQ(f[2], 1);
    EXPECT_EQ(f[0], 1 << o.lod_level(id));
    const BrickLattice l = o.lattice(o.node_brick(id));
    for (int a = 0; a < 3; ++a) EXPECT_LE(l.samples[a], o.max_brick_samples()[a]);
  }
}

}  // namespace
}  // namespace tsp

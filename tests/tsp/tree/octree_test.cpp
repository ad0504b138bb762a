#include "tsp/tree/octree.h"

#include <gtest/gtest.h>

#include <vector>

#include "tsp/core/error.h"

namespace tsp {
namespace {

// Every voxel of the grid is owned by exactly one brick, and a brick's samples hold its box
// plus at most one upper layer, never more than B per axis.
void check_bricks_tile(Dims d, int B) {
  Octree o(d, B);
  std::vector<int> owner(d.count(), 0);
  for (int b = 0; b < o.brick_count(); ++b) {
    Box own = o.brick_box(b), s = o.brick_samples(b);
    ASSERT_FALSE(own.empty());
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(s.lo[a], own.lo[a]);
      EXPECT_LE(s.size(a), B);
      EXPECT_TRUE(s.hi[a] == own.hi[a] || s.hi[a] == own.hi[a] + 1);
      EXPECT_LE(s.hi[a], d[a]);
    }
    for (int z = own.lo[2]; z < own.hi[2]; ++z)
      for (int y = own.lo[1]; y < own.hi[1]; ++y)
        for (int x = own.lo[0]; x < own.hi[0]; ++x) owner[x + d.x * (y + std::int64_t(d.y) * z)]++;
  }
  for (int c : owner) ASSERT_EQ(c, 1) << to_string(d) << " B=" << B;
}

TEST(Octree, BricksTileAnyGrid) {
  check_bricks_tile({64, 64, 64}, 32);
  check_bricks_tile({48, 48, 14}, 32);
  check_bricks_tile({1, 1, 1}, 32);
  check_bricks_tile({33, 2, 95}, 8);
  check_bricks_tile({100, 37, 5}, 16);
}

TEST(Octree, NodeBoxesAreUnionsOfChildrenAndLeavesAreBricks) {
  for (Dims d : {Dims{64, 64, 64}, Dims{48, 48, 14}, Dims{200, 30, 90}, Dims{5, 5, 5}}) {
    Octree o(d, 8);
    EXPECT_EQ(o.node(0).box, (Box{{0, 0, 0}, {d.x, d.y, d.z}}));
    int leaves = 0;
    for (int i = 0; i < o.size(); ++i) {
      const OctreeNode& n = o.node(i);
      if (n.is_leaf()) {
        ++leaves;
        EXPECT_EQ(n.box, o.brick_box(n.brick));
        EXPECT_EQ(o.brick_node(n.brick), i);
        continue;
      }
      std::int64_t sum = 0;
      int kids = 0;
      for (int c : n.children) {
        if (c < 0) continue;
        ++kids;
        sum += o.node(c).box.count();
        EXPECT_EQ(o.node(c).parent, i);
        EXPECT_EQ(o.node(c).level, n.level + 1);
        for (int a = 0; a < 3; ++a) {
          EXPECT_GE(o.node(c).box.lo[a], n.box.lo[a]);
          EXPECT_LE(o.node(c).box.hi[a], n.box.hi[a]);
        }
      }
      EXPECT_GE(kids, 2);
      EXPECT_EQ(sum, n.box.count());
    }
    EXPECT_EQ(leaves, o.brick_count());
  }
}

TEST(Octree, ThinGridSplitsOnlyThickAxes) {
  Octree o({48, 48, 14}, 16);  // 4 cells / 15 → 4 bricks in x and y, 1 in z
  EXPECT_EQ(o.brick_grid(), (std::array<int, 3>{4, 4, 1}));
  for (int oct = 4; oct < 8; ++oct) EXPECT_EQ(o.node(0).children[oct], -1);
  for (int oct = 0; oct < 4; ++oct) EXPECT_GE(o.node(0).children[oct], 0);
}

TEST(Octree, RejectsBadBrickSizes) {
  EXPECT_THROW(Octree({8, 8, 8}, 24), UsageError);
  EXPECT_THROW(Octree({8, 8, 8}, 2), UsageError);
  EXPECT_THROW(Octree({8, 8, 8}, 512), UsageError);
  EXPECT_THROW(Octree({0, 8, 8}, 32), UsageError);
}

}  // namespace
}  // namespace tsp

namespace tsp {
namespace {

TEST(Octree, CellsAreSpreadEvenlySoEdgeBricksAreNotSlivers) {
  Octree o({64, 64, 64}, 32);  // 63 cells: 3 bricks of 21, not 31 + 31 + 1
  EXPECT_EQ(o.brick_grid(), (std::array<int, 3>{3, 3, 3}));
  for (int b = 0; b < o.brick_count(); ++b) {
    Box s = o.brick_samples(b);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(s.size(a), 22) << "brick " << b;
  }
  EXPECT_EQ(o.max_brick_samples(), (std::array<int, 3>{22, 22, 22}));
  // x: 256 cells need ⌈256/31⌉ = 9 bricks of ⌈256/9⌉ = 29 cells (30 samples);
  // y: 32 cells are one too many for one brick of 32 samples → 2 bricks of 16 (17 samples);
  // z: 31 cells fit one brick of exactly B = 32 samples.
  Octree p({257, 33, 32}, 32);
  EXPECT_EQ(p.brick_grid(), (std::array<int, 3>{9, 2, 1}));
  EXPECT_EQ(p.brick_cells(0), 29);
  EXPECT_EQ(p.max_brick_samples(), (std::array<int, 3>{30, 17, 32}));
}

}  // namespace
}  // namespace tsp

namespace tsp {
namespace {

// stop_at (adaptive octrees): a flagged internal node becomes a leaf holding its level brick, at
// its own LOD level; the nodes below it keep their ids and boxes but are unreachable and their
// bricks absent; a second call replaces the first; flags below a stop are ignored.
TEST(Octree, StopAtMakesAStoppedNodeALeafOfItsLevelBrick) {
  Octree o({29, 29, 29}, 8);  // 4 bricks per axis: root, 8 children, 64 leaves
  ASSERT_EQ(o.size(), 73);
  const int c = o.node(0).children[3];
  const int level = o.lod_level(c);
  const int level_brick = o.node_brick(c);
  std::vector<std::uint8_t> flags(std::size_t(o.size()), 0);
  flags[std::size_t(c)] = 1;
  const int below = o.node(c).children[0];
  flags[std::size_t(below)] = 1;  // under a stop: ignored
  o.stop_at(flags);
  EXPECT_TRUE(o.has_stops());
  EXPECT_TRUE(o.stopped(c));
  EXPECT_FALSE(o.stopped(below));
  EXPECT_TRUE(o.node(c).is_leaf());
  EXPECT_EQ(o.node(c).brick, level_brick);
  EXPECT_EQ(o.node_brick(c), level_brick);
  EXPECT_EQ(o.lod_level(c), level);
  EXPECT_EQ(o.lattice(level_brick).factor[0], 1 << level);
  for (int k : o.node(c).children) EXPECT_EQ(k, -1);
  int unreachable = 0;
  for (int k : o.split_children(c)) {
    if (k < 0) continue;
    EXPECT_FALSE(o.reachable(k));
    EXPECT_EQ(o.stop_above(k), c);
    EXPECT_FALSE(o.brick_present(o.node_brick(k)));
    ++unreachable;
  }
  EXPECT_EQ(unreachable, 8);
  EXPECT_TRUE(o.reachable(c));
  EXPECT_TRUE(o.brick_present(level_brick));
  EXPECT_EQ(o.stop_above(0), -1);
  // Replaced: no stop at all restores the complete tree.
  o.stop_at(std::vector<std::uint8_t>(std::size_t(o.size()), 0));
  EXPECT_FALSE(o.has_stops());
  EXPECT_FALSE(o.node(c).is_leaf());
  EXPECT_EQ(o.node(c).children, o.split_children(c));
  EXPECT_TRUE(o.reachable(below));
  EXPECT_THROW(o.stop_at(std::vector<std::uint8_t>(3, 0)), UsageError);
}

}  // namespace
}  // namespace tsp

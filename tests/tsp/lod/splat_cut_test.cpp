// The splat cut against its definition, checked node by node: it covers the volume exactly once,
// a node is split exactly when it has children and projects to at least twice the minimum size,
// its area is the sum of its nodes' screen rectangles, and nodes a probe removed are not split.
#include "tsp/lod/splat_cut.h"

#include <gtest/gtest.h>

#include "tsp/lod/lod_error.h"

namespace tsp {
namespace {

Camera camera(Dims d, int width = 640, int height = 480) {
  CameraParams p;
  p.width = width;
  p.height = height;
  p.azimuth_deg = 30;
  p.elevation_deg = 20;
  return Camera(d, p);
}

// Per leaf brick, how many of itself and its ancestors are in the cut.
std::vector<int> coverage(const Octree& o, const std::vector<LodStop>& stops) {
  std::vector<int> n(std::size_t(o.brick_count()), 0);
  for (int id = 0; id < o.size(); ++id) {
    if (!o.node(id).is_leaf()) continue;
    for (int a = id; a >= 0; a = o.node(a).parent) n[std::size_t(o.node(id).brick)] += stops[std::size_t(a)] != LodStop::none;
  }
  return n;
}

TEST(SplatCut, MatchesItsDefinitionAtEveryMinimumSize) {
  const Octree o({129, 129, 129}, 16);
  const Camera cam = camera(o.dims());
  int previous = 0;
  for (double min_px : {1e9, 400.0, 200.0, 100.0, 50.0, 20.0, 0.0}) {
    const SplatCut cut = splat_cut(o, cam, min_px);
    ASSERT_EQ(int(cut.stops.size()), o.size());
    for (int k : coverage(o, cut.stops)) EXPECT_EQ(k, 1) << "min " << min_px;
    double area = 0;
    int size = 0;
    for (int id = 0; id < o.size(); ++id) {
      const double extent = projected_extent(o, cam, id);
      bool ancestor_in_cut = false;
      for (int a = o.node(id).parent; a >= 0; a = o.node(a).parent) ancestor_in_cut |= cut.stops[std::size_t(a)] != LodStop::none;
      if (ancestor_in_cut) {
        EXPECT_EQ(cut.stops[std::size_t(id)], LodStop::none);
        continue;
      }
      // Reached: in the cut unless split, split exactly when it has children and is large.
      const bool split = !o.node(id).is_leaf() && (min_px <= 0 || extent >= 2 * min_px);
      EXPECT_EQ(cut.stops[std::size_t(id)], split ? LodStop::none : LodStop::splat) << "node " << id;
      if (!split) {
        ++size;
        area += project_box(cam, geometric_box(o.node(id).box, o.dims())).pixel_area;
      }
    }
    EXPECT_EQ(cut.size, size);
    EXPECT_NEAR(cut.pixel_area, area, 1e-6 * area);
    EXPECT_GE(cut.size, previous);  // a smaller minimum never makes fewer splats
    previous = cut.size;
  }
  EXPECT_EQ(splat_cut(o, cam, 1e9).size, 1);
  EXPECT_EQ(splat_cut(o, cam, 0).size, o.brick_count());
}

// Within a budget: the cut's area stays within it (or the cut is the root alone), its node count
// within max_nodes, it covers the volume once, it is greedy — no node it split projects smaller
// than a node it could still split — and a larger budget never makes fewer splats.
TEST(SplatCut, WithinABudgetSplitsTheLargestSplatsFirst) {
  const Octree o({129, 97, 65}, 16);
  CameraParams p;
  p.width = 640;
  p.height = 480;
  p.azimuth_deg = 35;
  p.elevation_deg = 25;
  p.projection = Projection::perspective;
  const Camera cam(o.dims(), p);
  const double root = splat_cut(o, cam, 1e9).pixel_area;
  int previous = 0;
  for (double share : {0.0, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0, 1e9}) {
    const SplatCut cut = splat_cut_within(o, cam, share * root);
    for (int k : coverage(o, cut.stops)) EXPECT_EQ(k, 1) << "budget " << share;
    if (cut.size > 1) EXPECT_LE(cut.pixel_area, share * root * (1 + 1e-12)) << "budget " << share;
    double smallest_split = 1e300, largest_open = 0;
    for (int id = 0; id < o.size(); ++id) {
      bool in_or_below = false;  // the node or one of its ancestors is in the cut
      for (int a = id; a >= 0; a = o.node(a).parent) in_or_below |= cut.stops[std::size_t(a)] != LodStop::none;
      if (!in_or_below) smallest_split = std::min(smallest_split, projected_extent(o, cam, id));
      else if (cut.stops[std::size_t(id)] != LodStop::none && !o.node(id).is_leaf())
        largest_open = std::max(largest_open, projected_extent(o, cam, id));
    }
    if (cut.size > 1) EXPECT_GE(smallest_split, largest_open) << "budget " << share;
    EXPECT_NEAR(cut.min_px, 0.5 * largest_open, 1e-9);
    EXPECT_GE(cut.size, previous);
    previous = cut.size;
  }
  EXPECT_EQ(splat_cut_within(o, cam, 0).size, 1);
  EXPECT_EQ(splat_cut_within(o, cam, 1e300).size, o.brick_count());
  EXPECT_LE(splat_cut_within(o, cam, 1e300, {}, 20).size, 20);
}

TEST(SplatCut, NodesRemovedByAProbeAreNotSplit) {
  const Octree o({65, 65, 65}, 16);
  std::vector<ClipSide> clip(std::size_t(o.size()), ClipSide::kept);
  const int removed = o.node(0).children[0];
  clip[std::size_t(removed)] = ClipSide::removed;  // its whole subtree
  const SplatCut cut = splat_cut(o, camera(o.dims()), 0, clip);
  EXPECT_EQ(cut.stops[std::size_t(removed)], LodStop::splat);
  for (int k : coverage(o, cut.stops)) EXPECT_EQ(k, 1);
  // The removed node costs no area.
  const SplatCut open = splat_cut(o, camera(o.dims()), 0);
  EXPECT_LT(cut.pixel_area, open.pixel_area);
}

}  // namespace
}  // namespace tsp

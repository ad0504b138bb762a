// LaMar's selection filters (tsp/lod/selection_filter.h) against their definitions worked out
// here node by node (a node is in the cut exactly when no ancestor was drawn or ignored and it is
// drawn, ignored or a leaf), and the behaviour the paper describes: the distance filter is finest
// around the viewpoint and coarser with distance, the field-of-view filter leaves what lies
// outside the view coarse.
#include "tsp/lod/selection_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/core/geometry.h"

namespace tsp {
namespace {

constexpr double kPi = 3.14159265358979323846;

Camera placed(Dims d, std::array<double, 3> eye, double az = 30, double el = 20) {
  CameraParams p;
  p.width = 320;
  p.height = 240;
  p.azimuth_deg = az;
  p.elevation_deg = el;
  p.projection = Projection::perspective;
  p.eye = eye;
  return Camera(d, p);
}

std::array<double, 3> centre(const Octree& o, int id) {
  const Aabb b = geometric_box(o.node(id).box, o.dims());
  return {0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1]), 0.5 * (b.lo[2] + b.hi[2])};
}
double diagonal(const Octree& o, int id) {
  const Aabb b = geometric_box(o.node(id).box, o.dims());
  return std::sqrt((b.hi[0] - b.lo[0]) * (b.hi[0] - b.lo[0]) + (b.hi[1] - b.lo[1]) * (b.hi[1] - b.lo[1]) +
                   (b.hi[2] - b.lo[2]) * (b.hi[2] - b.lo[2]));
}
double dist(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// The cut a per-node answer gives, by the definition: stop at the first node drawn, ignored or
// a leaf on every path from the root.
template <class Stops>
std::vector<bool> expected_cut(const Octree& o, Stops stops_here) {
  std::vector<bool> in(std::size_t(o.size()), false);
  for (int id = 0; id < o.size(); ++id) {
    bool ancestors_refine = true;
    for (int a = o.node(id).parent; a >= 0; a = o.node(a).parent) ancestors_refine &= !stops_here(a);
    in[std::size_t(id)] = ancestors_refine && stops_here(id);
  }
  return in;
}

void expect_cut(const Octree& o, const LodCut& cut, const std::vector<bool>& want) {
  EXPECT_TRUE(cut.covers_once());
  for (int id = 0; id < o.size(); ++id) EXPECT_EQ(cut.contains(id), want[std::size_t(id)]) << "node " << id;
}

TEST(SelectionFilter, DistanceDrawsATileWhenTheEyeIsFartherThanKDiagonals) {
  const Octree o({129, 129, 129}, 16);
  for (double k : {0.5, 1.0, 2.0}) {
    for (std::array<double, 3> eye : {std::array<double, 3>{20, 30, 40}, {64, 64, 64}, {-200, -150, 90}}) {
      const Camera cam = placed(o.dims(), eye);
      const SelectionFilter f{LodFilter::distance, k};
      const auto stops = [&](int id) {
        return o.node(id).is_leaf() || dist(eye, centre(o, id)) > k * diagonal(o, id);
      };
      expect_cut(o, selection_cut(o, cam, f), expected_cut(o, stops));
    }
  }
}

TEST(SelectionFilter, DistanceIsFinestAroundTheEyeAndCoarserAway) {
  const Octree o({129, 129, 129}, 16);
  const std::array<double, 3> eye{20, 30, 40};
  const LodCut cut = selection_cut(o, placed(o.dims(), eye), {LodFilter::distance, 1});
  // The leaf holding the eye is drawn at full resolution.
  for (int id = 0; id < o.size(); ++id) {
    const Aabb b = geometric_box(o.node(id).box, o.dims());
    const bool holds = eye[0] >= b.lo[0] && eye[0] <= b.hi[0] && eye[1] >= b.lo[1] &&
                       eye[1] <= b.hi[1] && eye[2] >= b.lo[2] && eye[2] <= b.hi[2];
    if (holds && cut.contains(id)) EXPECT_TRUE(o.node(id).is_leaf()) << id;
  }
  // Mean distance of the cut's tiles grows with their size (tree level: root 0).
  std::map<int, std::pair<double, int>> by_level;
  for (int id : cut.nodes()) {
    auto& [sum, n] = by_level[o.node(id).level];
    sum += dist(eye, centre(o, id));
    ++n;
  }
  ASSERT_GE(by_level.size(), 3u);
  double nearer = 1e300;
  for (const auto& [level, s] : by_level) {  // deepest (smallest) tiles are nearest
    (void)level;
    const double mean = s.first / s.second;
    EXPECT_LT(mean, nearer + 1e-9) << "level " << level;
    nearer = mean;
  }
  // A larger K refines more.
  EXPECT_GT(selection_cut(o, placed(o.dims(), eye), {LodFilter::distance, 2}).size(), cut.size());
}

TEST(SelectionFilter, FovDrawsTilesUnderHalfTheFieldOfViewAndLeavesTheOutsideCoarse) {
  const Octree o({129, 129, 129}, 16);
  // From a corner inside the volume, looking along the view's direction: much of it is behind.
  const std::array<double, 3> eye{16, 100, 20};
  const Camera cam = placed(o.dims(), eye, 200, 10);
  for (double k : {1.0, 3.0}) {
    const SelectionFilter f{LodFilter::fov, k};
    const auto stops = [&](int id) {
      if (o.node(id).is_leaf()) return true;
      if (screen_footprint(cam, geometric_box(o.node(id).box, o.dims())).culled) return true;
      const double d = dist(eye, centre(o, id)), r = 0.5 * diagonal(o, id);
      const double beta = d > r ? 2 * std::asin(r / d) : kPi;
      return beta < 0.5 * (30 * kPi / 180) / k;
    };
    const LodCut cut = selection_cut(o, cam, f);
    expect_cut(o, cut, expected_cut(o, stops));
    // Tiles wholly outside the view are never refined below a node that was culled.
    int culled = 0;
    for (int id : cut.nodes())
      if (screen_footprint(cam, geometric_box(o.node(id).box, o.dims())).culled) {
        ++culled;
        const int p = o.node(id).parent;
        if (p >= 0) EXPECT_FALSE(screen_footprint(cam, geometric_box(o.node(p).box, o.dims())).culled);
      }
    EXPECT_GT(culled, 0);
  }
  // Orthographic: the screen rectangle's larger side against half the image height.
  CameraParams p;
  p.width = 320;
  p.height = 240;
  p.zoom = 3;
  const Camera ortho(o.dims(), p);
  const auto ortho_stops = [&](int id) {
    if (o.node(id).is_leaf()) return true;
    const ScreenFootprint s = screen_footprint(ortho, geometric_box(o.node(id).box, o.dims()));
    if (s.culled) return true;
    return std::max(s.rect[2] - s.rect[0], s.rect[3] - s.rect[1]) < 0.5 * 240;
  };
  expect_cut(o, selection_cut(o, ortho, {LodFilter::fov, 1}), expected_cut(o, ortho_stops));
}

TEST(SelectionFilter, ParsesNamesAndFactors) {
  EXPECT_EQ(parse_lod_filter("error", "--lod-filter"), SelectionFilter{});
  EXPECT_EQ(parse_lod_filter("distance", "--lod-filter"), (SelectionFilter{LodFilter::distance, 1}));
  EXPECT_EQ(parse_lod_filter("fov:2.5", "--lod-filter"), (SelectionFilter{LodFilter::fov, 2.5}));
  for (const char* bad : {"", "dist", "error:2", "fov:", "fov:0", "fov:-1", "distance:x", "fov:inf"})
    EXPECT_THROW(parse_lod_filter(bad, "--lod-filter"), UsageError) << bad;
  EXPECT_STREQ(to_string(LodFilter::fov), "fov");
}

TEST(Camera, APlacedEyeSitsWhereItIsPutAndLooksAlongTheView) {
  const Dims d{65, 33, 17};
  const Camera cam = placed(d, {10, 20, 5}, 30, 20);
  EXPECT_NEAR(cam.eye()[0], 10, 1e-9);
  EXPECT_NEAR(cam.eye()[1], 20, 1e-9);
  EXPECT_NEAR(cam.eye()[2], 5, 1e-9);
  // The same direction as the orbit camera of those angles.
  CameraParams p;
  p.azimuth_deg = 30;
  p.elevation_deg = 20;
  p.projection = Projection::perspective;
  const Camera orbit(d, p);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(cam.direction()[std::size_t(a)], orbit.direction()[std::size_t(a)], 1e-9);
  // A point just ahead of the eye projects to the image centre, in front of the near plane.
  const glm::dvec4 q = cam.view_projection() *
                       glm::dvec4(10 + cam.direction()[0], 20 + cam.direction()[1], 5 + cam.direction()[2], 1);
  EXPECT_NEAR(q.x / q.w, 0, 1e-9);
  EXPECT_NEAR(q.y / q.w, 0, 1e-9);
  EXPECT_GT(q.z / q.w, -1);
  EXPECT_LT(q.z / q.w, 1);
}

}  // namespace
}  // namespace tsp

// Dirty rectangles of partial-image reuse, GL-free: nothing changed → nothing to draw; one brick
// changed → rectangles that hold its whole projection and leave a far corner alone; every brick
// changed → the volume's projection.
#include "render/image_reuse.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "tsp/core/geometry.h"
#include "tsp/frame/frame_plan.h"

namespace tspgl {
namespace {

bool covered(const std::vector<PixelRect>& rects, double x, double y) {
  for (const PixelRect& r : rects)
    if (x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1) return true;
  return false;
}

glm::dvec2 project(const tsp::Camera& cam, double x, double y, double z) {
  const glm::dvec4 p = cam.view_projection() * glm::dvec4(x, y, z, 1.0);
  return {(p.x / p.w * 0.5 + 0.5) * cam.params().width, (p.y / p.w * 0.5 + 0.5) * cam.params().height};
}

TEST(ImageReuse, DirtyRectanglesCoverExactlyTheChangedBricks) {
  const tsp::TspTree tree({40, 40, 40}, 4, 8);  // 6³ bricks of 7 cells
  tsp::CameraParams p;
  p.width = 320;
  p.height = 240;
  const tsp::Camera cam(tree.octree().dims(), p);
  const int n = tree.octree().brick_count();
  BrickIdentities a(std::size_t(n), {0, 0}), b = a;
  EXPECT_TRUE(dirty_rects(tree, cam, a, b).empty());

  const int brick = 3 + 6 * (2 + 6 * 1);  // (3, 2, 1)
  b[std::size_t(brick)] = {7, 1};
  const auto rects = dirty_rects(tree, cam, a, b);
  ASSERT_FALSE(rects.empty());
  const tsp::Aabb box = tsp::geometric_box(tree.octree().brick_box(brick), tree.octree().dims());
  for (int c = 0; c < 8; ++c) {
    const glm::dvec2 s = project(cam, c & 1 ? box.hi[0] : box.lo[0], c & 2 ? box.hi[1] : box.lo[1],
                                 c & 4 ? box.hi[2] : box.lo[2]);
    EXPECT_TRUE(covered(rects, s.x, s.y)) << "corner " << c;
  }
  std::int64_t area = 0;
  for (const PixelRect& r : rects) area += r.area();
  EXPECT_LT(area, std::int64_t(p.width) * p.height / 4) << "one brick of 216 is a small part";
  EXPECT_FALSE(covered(rects, 1, 1));

  for (auto& id : b) id = {9, 9};
  const auto all = dirty_rects(tree, cam, a, b);
  const glm::dvec2 centre = project(cam, 19.5, 19.5, 19.5);
  EXPECT_TRUE(covered(all, centre.x, centre.y));
  EXPECT_LE(int(all.size()), kMaxDirtyRects);
}

// A level brick's identity holds, per leaf below it, how the page draws that leaf: a change of
// one leaf's page tag (a leaf turning flat inside a reused span) marks that leaf alone.
TEST(ImageReuse, LevelBrickIdentitiesFollowTheirLeafPages) {
  const tsp::TspTree tree({40, 40, 40}, 4, 8);
  const tsp::Octree& o = tree.octree();
  tsp::FramePlan plan;
  tsp::PlannedNode node;
  node.node = {0, 0, tree.time().span(0)};
  node.cls = tsp::DrawClass::reused_texture;
  node.texture_count = 1;
  plan.nodes.push_back(node);
  plan.textures.push_back({tsp::texture_key(o, o.node_brick(0), 0), 0, false});
  const auto colour = [](int) { return tsp::Rgba{}; };
  std::vector<std::int64_t> pages(std::size_t(o.brick_count()), 5);
  const BrickIdentities a = brick_identities(tree, plan, colour, pages);
  pages[7] = 6;
  const BrickIdentities b = brick_identities(tree, plan, colour, pages);
  for (int k = 0; k < o.brick_count(); ++k)
    EXPECT_EQ(a[std::size_t(k)] == b[std::size_t(k)], k != 7) << "brick " << k;
  // Without page tags every leaf below the root has the root's level identity.
  const BrickIdentities c = brick_identities(tree, plan, colour);
  for (int k = 1; k < o.brick_count(); ++k) EXPECT_EQ(c[std::size_t(k)], c[0]);
}

}  // namespace
}  // namespace tspgl

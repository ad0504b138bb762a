// The progressive refinement's bands (render/tile_refinement.h): every row drawn exactly once,
// the middle first, at least one band a frame, as many as the last frame's time per pixel fits.
#include <gtest/gtest.h>

#include <vector>

#include "render/tile_refinement.h"

namespace {

using tspgl::kRefineBand;
using tspgl::PixelRect;
using tspgl::TileRefinement;

TEST(TileRefinement, CoversEveryRowOnceMiddleFirst) {
  TileRefinement t;
  EXPECT_FALSE(t.active());
  EXPECT_FALSE(t.done());
  t.start(100, 150);  // 5 bands: rows 0-31, ..., 128-149
  EXPECT_EQ(t.bands(), 5);
  std::vector<int> rows(150, 0);
  bool first = true;
  while (t.active()) {
    const std::vector<PixelRect> rects = t.next(0);  // no time: one band a frame
    ASSERT_EQ(rects.size(), 1u);
    if (first) {
      EXPECT_EQ(rects[0].y0, 2 * kRefineBand) << "the middle band first";
    }
    first = false;
    EXPECT_EQ(rects[0].x0, 0);
    EXPECT_EQ(rects[0].x1, 100);
    for (int y = rects[0].y0; y < rects[0].y1; ++y) ++rows[std::size_t(y)];
    t.drawn(10);
  }
  EXPECT_TRUE(t.done());
  EXPECT_TRUE(t.next(1e9).empty());
  for (int n : rows) EXPECT_EQ(n, 1);
}

TEST(TileRefinement, FirstFrameDrawsAQuarterThenFollowsTheTimePerPixel) {
  TileRefinement t;
  t.start(64, 256);  // 8 bands of 2048 pixels
  std::vector<PixelRect> r = t.next(1000);
  std::int64_t px = 0;
  for (const PixelRect& p : r) px += p.area();
  EXPECT_EQ(px, 64 * 256 / 4);  // kRefineFirstShare
  EXPECT_EQ(r.size(), 1u) << "adjacent bands are one rectangle";
  t.drawn(8);  // 8 ms for 4096 pixels: 2048 pixels cost 4 ms
  r = t.next(8);
  px = 0;
  for (const PixelRect& p : r) px += p.area();
  EXPECT_EQ(px, 2 * 2048);
  t.drawn(4);
  EXPECT_FALSE(t.last_handed_out());
  r = t.next(1e9);  // the rest at once
  EXPECT_TRUE(t.last_handed_out());
  EXPECT_TRUE(t.done());
  t.stop();
  EXPECT_FALSE(t.done());
}

}  // namespace

// The TF editor's handles (src/player/tf_handles.h): moving one warps the detailed auto map
// in place between its neighbours (it used to become straight segments through the handles);
// a piecewise-linear map stays what from_points makes of its moved knots.
#include "player/tf_handles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tsp/metric/histogram_tf.h"
#include "tsp/metric/tf_io.h"

namespace {

using namespace tspplayer;

// The auto map of a bumpy histogram: many knots, so evenly spaced handles.
tsp::TransferFunction auto_map() {
  static std::vector<std::uint64_t> counts;
  counts.clear();
  for (int i = 0; i < 256; ++i)
    counts.push_back(std::uint64_t(1000 + 900 * std::sin(i * 0.3) + (i * 7919 % 613) * 3));
  return tsp::histogram_transfer_function({counts, {0, 1}}, {0, 1});
}

// Entries bent away from the straight line through their neighbours (curve detail).
int bends(const tsp::TransferFunction& tf, int from, int to) {
  int n = 0;
  for (int j = std::max(1, from); j < std::min(tf.size() - 1, to); ++j)
    n += std::fabs(tf.entry(j + 1).a - 2 * tf.entry(j).a + tf.entry(j - 1).a) > 1e-4f;
  return n;
}

TEST(PlayerTfHandles, DraggingAHandleWarpsTheAutoMapInPlace) {
  const tsp::TransferFunction tf = auto_map();
  const TfHandles h = place_handles(tf);
  ASSERT_EQ(int(h.placed.size()), kSampledHandles);
  std::vector<tsp::TfPoint> moved = h.placed;
  // Untouched: the map itself, exactly.
  const tsp::TransferFunction same = warp_handles(h, moved);
  for (int j = 0; j < tf.size(); ++j) EXPECT_EQ(same.entry(j), tf.entry(j)) << j;
  // Handle 4 up by 0.2 and to the right.
  moved[4].c.a = std::min(1.f, moved[4].c.a + 0.2f);
  moved[4].x = clamp_handle_x(moved, 4, moved[4].x + 0.05);
  const tsp::TransferFunction warped = warp_handles(h, moved);
  int changed_inside = 0;
  for (int j = 0; j < tf.size(); ++j) {
    const double v = tf.entry_value(j);
    if (v <= h.placed[3].x || v >= h.placed[5].x)  // beyond the neighbours: as it was
      EXPECT_EQ(warped.entry(j), tf.entry(j)) << j;
    else
      changed_inside += !(warped.entry(j) == tf.entry(j));
  }
  EXPECT_GT(changed_inside, 20);
  // The detail stays: the warped span bends as often as the map did there (straight segments
  // through the handles, the old editor's result, bend at the handles only).
  const int j3 = tf.size() * 3 / 8, j5 = tf.size() * 5 / 8;
  EXPECT_GE(bends(warped, j3 + 2, j5 - 2), bends(tf, j3 + 2, j5 - 2) / 2);
  EXPECT_GT(bends(tf, j3 + 2, j5 - 2), 10);
  const tsp::TransferFunction straight = tsp::TransferFunction::from_points(tf.domain(), moved);
  EXPECT_LE(bends(straight, j3 + 2, j5 - 2), 4);  // at the handles only
  // At the moved handle the map has the handle's opacity.
  EXPECT_NEAR(sample_tf(warped, moved[4].x).a, moved[4].c.a, 0.01);
}

TEST(PlayerTfHandles, APiecewiseLinearMapStaysWhatFromPointsMakes) {
  const std::vector<tsp::TfPoint> pts = {{0.0, {0, 0, 1, 0}}, {0.4, {0, 1, 0, 0.5}},
                                         {1.0, {1, 0, 0, 1}}};
  const tsp::TransferFunction tf = tsp::TransferFunction::from_points({0, 1}, pts);
  TfHandles h = place_handles(tf);
  ASSERT_EQ(h.placed.size(), 3u);
  std::vector<tsp::TfPoint> moved = h.placed;
  moved[1].x = 0.6;
  moved[1].c.a = 0.2f;
  const tsp::TransferFunction warped = warp_handles(h, moved);
  const tsp::TransferFunction expected = tsp::TransferFunction::from_points({0, 1}, moved);
  for (int j = 0; j < tf.size(); ++j) EXPECT_NEAR(warped.entry(j).a, expected.entry(j).a, 5e-3) << j;
  // Handles keep their order: the middle one stops at its neighbours.
  EXPECT_EQ(clamp_handle_x(moved, 1, 1.5), moved[2].x);
  EXPECT_EQ(clamp_handle_x(moved, 1, -1), moved[0].x);
}

TEST(PlayerTfHandles, AddingBendsTowardsTheNewPointAndRemovingStraightens) {
  const tsp::TransferFunction tf = auto_map();
  TfHandles h = place_handles(tf);
  std::vector<tsp::TfPoint> points = h.placed;
  const int i = add_handle(h, points, tf, 0.3, {1, 1, 1, 0.9f});
  ASSERT_EQ(points.size(), std::size_t(kSampledHandles + 1));
  EXPECT_EQ(points[std::size_t(i)].x, 0.3);
  const tsp::TransferFunction added = warp_handles(h, points);
  EXPECT_NEAR(sample_tf(added, 0.3).a, 0.9, 0.03);
  EXPECT_EQ(added.entry(tf.size() - 1), tf.entry(tf.size() - 1));  // far away: unchanged
  const tsp::TransferFunction removed = remove_handle(h, points, added, i);
  EXPECT_EQ(points.size(), std::size_t(kSampledHandles));
  // Straight between the neighbours now.
  const double lo = points[std::size_t(i - 1)].x, hi = points[std::size_t(i)].x;
  const double mid = 0.5 * (lo + hi);
  EXPECT_NEAR(sample_tf(removed, mid).a,
              0.5 * (points[std::size_t(i - 1)].c.a + points[std::size_t(i)].c.a), 0.01);
}

// A colour range typed or fitted keeps every handle, each at its place relative to the domain
// with its colour, whatever the table's knots do (placed again from the stretched table, a moved
// handle went back to its even place and a fit left 7 points of 9).
TEST(PlayerTfHandles, ARangeChangeKeepsEveryHandleInItsPlace) {
  const tsp::TransferFunction tf = auto_map();
  std::vector<tsp::TfPoint> points = place_handles(tf).placed;
  points[2].x = 0.2;  // a moved handle (its even place is 0.25)
  const tsp::TransferFunction wide = tsp::rescaled(tf, {0.3, 2.5});
  const TfHandles h = rescale_handles(points, tf.domain(), wide);
  ASSERT_EQ(h.placed.size(), points.size());
  EXPECT_EQ(h.base.domain().lo, 0.3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR((h.placed[i].x - 0.3) / 2.2, points[i].x, 1e-12) << i;
    EXPECT_EQ(h.placed[i].c.a, points[i].c.a) << i;
  }
  // And back: where they were.
  const TfHandles back = rescale_handles(h.placed, wide.domain(), tsp::rescaled(wide, {0, 1}));
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_NEAR(back.placed[i].x, points[i].x, 1e-12);
}

}  // namespace

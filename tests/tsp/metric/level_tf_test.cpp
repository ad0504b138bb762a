// The coarse levels' TF (tsp/metric/level_tf.h): the row ladder, and the blurred entries
// against the expected colour of a normal distribution of values worked out independently.
#include "tsp/metric/level_tf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace tsp {
namespace {

TEST(LevelTf, RowsRunGeometricallyAndTheNearestRowIsPicked) {
  EXPECT_EQ(level_tf_sigma(0), 0.0);
  EXPECT_DOUBLE_EQ(level_tf_sigma(1), kLevelTfSigmaMin);
  EXPECT_NEAR(level_tf_sigma(kLevelTfRows - 1), kLevelTfSigmaMax, 1e-12);
  for (int r = 1; r < kLevelTfRows; ++r) {
    EXPECT_EQ(level_tf_row(level_tf_sigma(r)), r);
    if (r > 1) EXPECT_GT(level_tf_sigma(r), level_tf_sigma(r - 1));
  }
  EXPECT_EQ(level_tf_row(0), 0);
  EXPECT_EQ(level_tf_row(0.4 * kLevelTfSigmaMin), 0);
  EXPECT_EQ(level_tf_row(std::nan("")), 0);
  EXPECT_EQ(level_tf_row(10.0), kLevelTfRows - 1);
}

TEST(LevelTf, BlurredEntriesAreTheExpectedColourOfTheSpread) {
  // One opaque red entry in the middle of 64 transparent ones (a thin band).
  const int k = 64;
  const std::vector<TfPoint> clear{{0, {0, 0, 1, 0}}, {1, {0, 0, 1, 0}}};
  TransferFunction tf = TransferFunction::from_points({0, 1}, clear, k);
  tf.set_entry(32, {1, 0, 0, 0.8f});
  EXPECT_EQ(blurred_entries(tf, 0), std::vector<Rgba>(tf.entries().begin(), tf.entries().end()));
  const double sigma = 2.0 / k;  // two entries
  const std::vector<Rgba> b = blurred_entries(tf, sigma);
  // Entry j's opacity: 0.8 × the normalised weight of entry 32 at distance j − 32.
  double norm = 0;
  for (int d = -6; d <= 6; ++d) norm += std::exp(-0.5 * (d / 2.0) * (d / 2.0));
  double total = 0;
  for (int j = 0; j < k; ++j) {
    const double d = j - 32;
    const double want = std::abs(d) <= 6 ? 0.8 * std::exp(-0.5 * (d / 2.0) * (d / 2.0)) / norm : 0;
    EXPECT_NEAR(b[std::size_t(j)].a, want, 1e-6) << j;
    if (want > 0) {
      EXPECT_FLOAT_EQ(b[std::size_t(j)].r, 1.f) << j;  // the band's colour, not the blue
      EXPECT_FLOAT_EQ(b[std::size_t(j)].b, 0.f) << j;
    }
    total += b[std::size_t(j)].a;
  }
  EXPECT_NEAR(total, 0.8, 1e-6);  // the band keeps its weight, spread wider and fainter
  // At the domain's edge the values beyond it take the edge entry (the lookup clamps).
  const std::vector<TfPoint> green{{0, {0, 1, 0, 0.5f}}, {1, {0, 1, 0, 0.5f}}};
  const TransferFunction edge = TransferFunction::from_points({0, 1}, green, k);
  for (const Rgba& e : blurred_entries(edge, 0.1)) EXPECT_NEAR(e.a, 0.5, 1e-6);
}

}  // namespace
}  // namespace tsp

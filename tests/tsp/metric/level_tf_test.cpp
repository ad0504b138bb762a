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

// The data's prior: an opaque entry no sample takes, beside a clear one most samples take. The
// plain blur spreads the opaque entry's opacity over the clear one; weighted by the prior (the
// counts plus the mean count) the clear entry stays nearly clear, as worked out here.
TEST(LevelTf, ThePriorKeepsACommonClearValueClearBesideARareOpaqueOne) {
  TransferFunction tf({0, 8}, 8);
  std::vector<Rgba> e(8, Rgba{1, 1, 1, 0});
  e[4].a = 1;  // opaque, taken by no sample
  tf.set_entries(0, e);
  const std::vector<std::uint64_t> counts{0, 0, 0, 1000, 0, 0, 0, 0};
  const std::vector<double> prior = entry_prior(tf, counts, {0, 8});
  ASSERT_EQ(prior.size(), 8u);
  EXPECT_DOUBLE_EQ(prior[3], 1000 + kLevelTfPriorFloor * 125);
  EXPECT_DOUBLE_EQ(prior[0], kLevelTfPriorFloor * 125);
  const double sigma = 1.0 / 8;  // one entry
  const std::vector<Rgba> plain = blurred_entries(tf, sigma), weighted = blurred_entries(tf, sigma, prior);
  // Entry 3's expected opacity under the prior-weighted kernel, summed here.
  double num = 0, den = 0;
  for (int i = 0; i < 8; ++i) {
    const double w = std::exp(-0.5 * (i - 3) * (i - 3)) * prior[std::size_t(i)];
    num += w * e[std::size_t(i)].a;
    den += w;
  }
  EXPECT_NEAR(weighted[3].a, num / den, 1e-3);  // (the kernel is cut at a few σ)
  EXPECT_LT(weighted[3].a, 0.5 * plain[3].a);
  EXPECT_GT(plain[3].a, 0.2f);
  // Without a histogram: the plain blur.
  EXPECT_TRUE(entry_prior(tf, {}, {0, 8}).empty());
  const std::vector<Rgba> none = blurred_entries(tf, sigma, {});
  for (int i = 0; i < 8; ++i) EXPECT_EQ(none[std::size_t(i)].a, plain[std::size_t(i)].a);
}

}  // namespace
}  // namespace tsp

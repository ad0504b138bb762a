// The histogram-built default TF (tsp/metric/histogram_tf.h): rarity against hand-worked
// histograms (plateaus, empty bins, a geometric fall-off, flat counts), the opacity law, the
// colours at the ends of the domain and a domain over part of the data.
#include "tsp/metric/histogram_tf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/metric/tf_io.h"

namespace tsp {
namespace {

constexpr int kBins = 64;

// A two-state field (a shock): two plateaus of equal counts with nothing between them.
std::vector<std::uint64_t> two_states() {
  std::vector<std::uint64_t> c(kBins, 0);
  for (int i = 0; i < 16; ++i) c[std::size_t(i)] = 1000000;
  for (int i = 48; i < kBins; ++i) c[std::size_t(i)] = 1000000;
  return c;
}

TEST(HistogramTf, PlateausAreClearAndTheEmptyGapBetweenThemIsOpaque) {
  const std::vector<std::uint64_t> c = two_states();
  const std::vector<double> r = histogram_rarity(c);
  ASSERT_EQ(r.size(), c.size());
  // Inside a plateau, farther than the filter's half-width from its edge: the largest count.
  for (int i : {0, 5, 13, 50, 63}) EXPECT_NEAR(r[std::size_t(i)], 0.0, 1e-12) << i;
  // In the gap, farther than the half-width from either plateau: no sample after smoothing.
  for (int i = 16 + kHistogramTfSmoothBins; i < 48 - kHistogramTfSmoothBins; ++i)
    EXPECT_EQ(r[std::size_t(i)], 1.0) << i;
  // At the edge the triangular filter (weights 1 2 3 2 1, /9) leaves 6/9 of the count at bin 15
  // and 1/9 at bin 17; their rarities follow the log law between the extremes. The least L of
  // the bins holding samples is bin 17's (and 46's).
  const double lmax = std::log1p(1e6), lmin = std::log1p(1e6 / 9);
  EXPECT_NEAR(r[15], (lmax - std::log1p(6e6 / 9)) / (lmax - lmin), 1e-12);
  EXPECT_NEAR(r[17], 1.0, 1e-12);

  const TransferFunction tf = histogram_transfer_function({c, {0, 64}}, {0, 64}, kBins);
  EXPECT_EQ(tf.entry(32).a, float(kHistogramTfMaxOpacity));  // the front between the states
  EXPECT_EQ(tf.entry(3).a, 0.0f);   // the states themselves (a share 3.5/32 below: no tail)
  EXPECT_EQ(tf.entry(60).a, 0.0f);  // (3.5/32 above)
  // The lowest values of the low state are its tail: 0.5/32 of the samples below bin 0.
  EXPECT_NEAR(tf.entry(0).a, kHistogramTfMaxOpacity * std::pow(1 - (0.5 / 32) / kHistogramTfTailShare, 2),
              1e-6);
  ASSERT_GT(r[15], kHistogramTfClearRarity);
  EXPECT_NEAR(tf.entry(15).a, kHistogramTfMaxOpacity * std::pow(r[15], kHistogramTfGamma), 1e-6);
  // Bin 14 keeps 8/9 of the count: rarity log(9/8)/log(9) = 0.054, under the clear threshold.
  EXPECT_NEAR(r[14], std::log(9.0 / 8) / std::log(9.0), 1e-6);
  EXPECT_EQ(tf.entry(14).a, 0.0f);
}

TEST(HistogramTf, RarerValuesAreMoreOpaqueAndColoursRunCoolToWarm) {
  // Counts falling by a factor 2 a bin, as a vorticity's tail: opacity rises with the value.
  std::vector<std::uint64_t> c(40);
  for (int i = 0; i < 40; ++i) c[std::size_t(i)] = std::uint64_t(1) << (40 - i);
  const std::vector<double> r = histogram_rarity(c);
  for (int i = 1; i < 40; ++i) EXPECT_GT(r[std::size_t(i)], r[std::size_t(i - 1)]) << i;
  EXPECT_NEAR(r[0], 0.0, 1e-12);
  EXPECT_NEAR(r[39], 1.0, 1e-12);
  const TransferFunction tf = histogram_transfer_function({c, {-1, 1}}, {-1, 1}, 40);
  for (int j = 1; j < 40; ++j) EXPECT_GE(tf.entry(j).a, tf.entry(j - 1).a) << j;
  // Cool to Warm's end points (ParaView) at the domain's first and last entries' centres.
  EXPECT_NEAR(tf.entry(0).b, 0.754, 0.02);
  EXPECT_NEAR(tf.entry(0).r, 0.230, 0.02);
  EXPECT_NEAR(tf.entry(39).r, 0.706, 0.02);
  EXPECT_NEAR(tf.entry(39).b, 0.150, 0.02);
}

TEST(HistogramTf, FlatOrEmptyCountsGiveOneHalfRarityNeverAnEmptyMap) {
  const std::vector<std::uint64_t> flat(32, 500), none(32, 0);
  for (double x : histogram_rarity(flat)) EXPECT_EQ(x, kHistogramTfFlatRarity);
  for (double x : histogram_rarity(none)) EXPECT_EQ(x, kHistogramTfFlatRarity);
  const TransferFunction tf = histogram_transfer_function({flat, {0, 1}}, {0, 1}, 16);
  const float a = float(kHistogramTfMaxOpacity * std::pow(kHistogramTfFlatRarity, kHistogramTfGamma));
  // Entry j holds bin 2j + 1; the first and last are in the tails (1.5/32 below, 0.5/32 above).
  for (int j = 1; j < 15; ++j) EXPECT_FLOAT_EQ(tf.entry(j).a, a) << j;
  const auto tail = [](double s) {
    return float(kHistogramTfMaxOpacity * std::pow(1 - s / kHistogramTfTailShare, kHistogramTfGamma));
  };
  EXPECT_FLOAT_EQ(tf.entry(0).a, tail(1.5 / 32));
  EXPECT_FLOAT_EQ(tf.entry(15).a, tail(0.5 / 32));
  const TransferFunction empty = histogram_transfer_function({none, {0, 1}}, {0, 1}, 16);
  for (int j = 0; j < 16; ++j) EXPECT_FLOAT_EQ(empty.entry(j).a, a) << j;
}

TEST(HistogramTf, TailShareIsTheNearerSidesShareOfTheSamples) {
  const std::vector<std::uint64_t> c{1, 2, 3, 4};  // F at the bins' middles: .05 .2 .45 .8
  const std::vector<double> s = histogram_tail_share(c);
  const double want[4] = {0.05, 0.2, 0.45, 0.2};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(s[std::size_t(i)], want[i], 1e-12) << i;
  for (double x : histogram_tail_share(std::vector<std::uint64_t>(5, 0))) EXPECT_EQ(x, 1.0);
}

TEST(HistogramTf, ADomainOverOnePlateauTakesTheRarityAmongItsOwnBins) {
  // Over [0, 12] only the first plateau is in the domain (bins 0-12): flat, so half rarity, not
  // clear; its lowest bin is the tail of those bins (0.5/13 of their samples below it).
  const std::vector<std::uint64_t> c = two_states();
  const TransferFunction tf = histogram_transfer_function({c, {0, 64}}, {0, 12}, 16);
  const float a = float(kHistogramTfMaxOpacity * std::pow(kHistogramTfFlatRarity, kHistogramTfGamma));
  for (int j = 1; j < 16; ++j) EXPECT_FLOAT_EQ(tf.entry(j).a, a) << j;
  EXPECT_FLOAT_EQ(tf.entry(0).a, float(kHistogramTfMaxOpacity *
                                       std::pow(1 - (0.5 / 13) / kHistogramTfTailShare, 2)));
  // Values outside the histogram's span: no sample takes them, rarity 1.
  const TransferFunction out = histogram_transfer_function({c, {0, 64}}, {100, 200}, 8);
  for (int j = 0; j < 8; ++j) EXPECT_FLOAT_EQ(out.entry(j).a, float(kHistogramTfMaxOpacity));
}

TEST(HistogramTf, AutoPresetNeedsAHistogramAndBadRangesAreUsageErrors) {
  const std::vector<std::uint64_t> c = two_states();
  const ValueHistogram h{c, {0, 64}};
  EXPECT_THROW(preset_transfer_function(kAutoPreset, {0, 64}), UsageError);
  const TransferFunction tf = preset_transfer_function(kAutoPreset, {0, 64}, kBins, &h);
  EXPECT_EQ(tf.entry(32).a, float(kHistogramTfMaxOpacity));
  EXPECT_EQ(transfer_function_from_arg("preset:auto", {0, 64}, kBins, {}, &h).entry(3).a, 0.0f);
  EXPECT_EQ(preset_names().front(), kAutoPreset);
  EXPECT_THROW(histogram_transfer_function(h, {1, 1}), UsageError);
  EXPECT_THROW(histogram_transfer_function({c, {0, NAN}}, {0, 1}), UsageError);
}

}  // namespace
}  // namespace tsp

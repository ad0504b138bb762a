#include "tsp/metric/compute_errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "support/memory_tree.h"
#include "tsp/core/error.h"
#include "tsp/metric/approximate_metric.h"
#include "tsp/metric/reference_metric.h"
#include "tsp/metric/tf_io.h"

namespace tsp {
namespace {

using tsptest::MemoryBrickStore;
using tsptest::MemorySeries;

constexpr Metric kAll[] = {Metric::scalar, Metric::reference, Metric::approximate,
                           Metric::perceptual};

TEST(Metrics, NamesRoundTripAndUnknownIsAUsageError) {
  for (Metric m : kAll) EXPECT_EQ(parse_metric(to_string(m)), m);
  EXPECT_THROW(parse_metric("colour"), UsageError);
}

TEST(Metrics, ConstantDataHasZeroSpatialErrorForEveryMetric) {
  auto s = MemorySeries::generate({20, 11, 7}, 4, [](int, int, int, int) { return -3.5f; });
  MemoryBrickStore store(s, 8, ValueRange{-10, 10});
  const TransferFunction tf = preset_transfer_function("filled", {-10, 10});
  for (Metric m : kAll) {
    const MetricResult r = compute_errors(m, store.tree(), tf, &store, 2);
    ASSERT_EQ(int(r.errors.spatial.size()), store.tree().size());
    for (int id = 0; id < store.tree().size(); ++id) {
      EXPECT_EQ(r.errors.spatial[id], 0.0f) << to_string(m) << " " << id;
      EXPECT_EQ(r.errors.temporal[id], 0.0f) << to_string(m) << " " << id;
      EXPECT_FALSE(r.transparent[id]);
    }
  }
}

TEST(Metrics, EveryMetricAppliesTheSameExactTransparencyTest) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0, 1);
  // Values rise along x across the bricks, so a sparse TF hides some nodes and not others.
  auto s = MemorySeries::generate({30, 8, 8}, 3, [&](int, int x, int, int) { return x + u(rng); });
  MemoryBrickStore store(s, 8);
  const TransferFunction tf = preset_transfer_function("sparse", store.tree().value_range());
  std::vector<std::uint8_t> expected;
  for (int id = 0; id < store.tree().size(); ++id) {
    const EntryRange r = entry_range(tf, store.tree().stats(id));
    bool clear = true;
    for (int j = r.lo; j <= r.hi; ++j) clear = clear && tf.entry(j).a == 0;
    expected.push_back(clear);
  }
  const std::int64_t want = std::count(expected.begin(), expected.end(), 1);
  ASSERT_GT(want, 0);
  ASSERT_LT(want, store.tree().size());
  for (Metric m : kAll) {
    const MetricResult r = compute_errors(m, store.tree(), tf, &store);
    EXPECT_EQ(r.transparent, expected) << to_string(m);
    EXPECT_EQ(r.transparent_count(), want);
    for (int id = 0; id < store.tree().size(); ++id)
      if (expected[id]) {
        EXPECT_EQ(r.errors.spatial[id], 0.0f);
        EXPECT_EQ(r.errors.temporal[id], 0.0f);
      }
  }
}

TEST(Metrics, WholeTreeResultsEqualThePerNodeComputations) {
  std::mt19937 rng(4);
  std::normal_distribution<float> n(5, 2);
  auto s = MemorySeries::generate({17, 17, 17}, 5, [&](int, int, int, int) { return n(rng); });
  MemoryBrickStore store(s, 8);
  const TransferFunction tf = preset_transfer_function("filled", store.tree().value_range());
  for (Metric m : {Metric::scalar, Metric::approximate, Metric::perceptual}) {
    const MetricResult one = compute_errors(m, store.tree(), tf, nullptr, 1);
    const MetricResult two = compute_errors(m, store.tree(), tf, nullptr, 2);
    const ApproximateMetric am(m, tf);
    for (int id = 0; id < store.tree().size(); ++id) {
      const NodeResult r = am.evaluate(store.tree().stats(id));
      EXPECT_EQ(one.errors.spatial[id], r.spatial);
      EXPECT_EQ(two.errors.spatial[id], r.spatial);
      EXPECT_EQ(two.errors.temporal[id], r.temporal);
      EXPECT_EQ(two.mean_colour[id], r.mean);
    }
  }
  const MetricResult ref = compute_errors(Metric::reference, store.tree(), tf, &store, 2);
  ReferenceMetric rm(store);
  rm.update(tf, 1);
  for (int id = 0; id < store.tree().size(); ++id) {
    EXPECT_EQ(ref.errors.spatial[id], rm.node(id).spatial);
    EXPECT_EQ(ref.errors.temporal[id], rm.node(id).temporal);
  }
  EXPECT_THROW(compute_errors(Metric::reference, store.tree(), tf, nullptr), UsageError);
}

}  // namespace
}  // namespace tsp

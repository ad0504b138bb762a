#include "tsp/metric/reference_metric.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "support/memory_tree.h"
#include "tsp/core/error.h"

namespace tsp {
namespace {

using tsptest::MemoryBrickStore;
using tsptest::MemorySeries;

// A TF with varied colours, a transparent band and a partly transparent ramp.
TransferFunction test_tf(ValueRange domain, int k = 64) {
  TransferFunction tf(domain, k);
  for (int j = 0; j < k; ++j) {
    const float t = float(j) / (k - 1);
    const float a = (j >= k / 4 && j < k / 3) ? 0.0f : t * t;
    tf.set_entry(j, {t, 1 - t, 0.5f + 0.5f * std::sin(9 * t), a});
  }
  return tf;
}

// Eq. 7.
double dist(const Rgba& c1, const double* c2) {
  return c1.a * ((c1.r - c2[0]) * (c1.r - c2[0]) + (c1.g - c2[1]) * (c1.g - c2[1]) +
                 (c1.b - c2[2]) * (c1.b - c2[2])) +
         (c1.a - c2[3]) * (c1.a - c2[3]);
}

// The spec's reference formulas computed literally, two passes per node and per voxel, over the
// decoded samples of every voxel the node owns.
NodeResult brute_force(const MemoryBrickStore& store, const TransferFunction& tf, int id) {
  const TspTree& tree = store.tree();
  const Box box = tree.octree().node(tree.octree_of(id)).box;
  const Span sp = tree.time().span(tree.time_of(id));
  NodeResult out;
  const NodeStats& st = tree.stats(id);
  if (tf.transparent(tf.entry_of(st.min), tf.entry_of(st.max))) {
    out.transparent = true;
    return out;
  }
  auto colour = [&](int t, int x, int y, int z) { return tf.lookup(store.decoded(t, x, y, z)); };
  double mean[4] = {0, 0, 0, 0}, n = 0;
  for (int z = box.lo[2]; z < box.hi[2]; ++z)
    for (int y = box.lo[1]; y < box.hi[1]; ++y)
      for (int x = box.lo[0]; x < box.hi[0]; ++x)
        for (int t = sp.t0; t <= sp.t1; ++t) {
          const Rgba c = colour(t, x, y, z);
          mean[0] += c.r, mean[1] += c.g, mean[2] += c.b, mean[3] += c.a, n += 1;
        }
  for (double& v : mean) v /= n;
  double dev = 0, temporal = 0, voxels = 0;
  for (int z = box.lo[2]; z < box.hi[2]; ++z)
    for (int y = box.lo[1]; y < box.hi[1]; ++y)
      for (int x = box.lo[0]; x < box.hi[0]; ++x) {
        double vm[4] = {0, 0, 0, 0};
        for (int t = sp.t0; t <= sp.t1; ++t) {
          const Rgba c = colour(t, x, y, z);
          dev += dist(c, mean);
          vm[0] += c.r, vm[1] += c.g, vm[2] += c.b, vm[3] += c.a;
        }
        for (double& v : vm) v /= sp.length();
        double vdev = 0;
        for (int t = sp.t0; t <= sp.t1; ++t) vdev += dist(colour(t, x, y, z), vm);
        const double fi =
            std::sqrt(vm[3] * (vm[0] * vm[0] + vm[1] * vm[1] + vm[2] * vm[2]) + vm[3] * vm[3]);
        if (fi > 0) temporal += std::sqrt(vdev / sp.length()) / fi;
        voxels += 1;
      }
  const double f = std::sqrt(mean[3] * (mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]) +
                             mean[3] * mean[3]);
  out.spatial = f > 0 ? float(std::sqrt(dev / n) / f) : 0.0f;
  out.temporal = float(temporal / voxels);
  out.mean = {float(mean[0]), float(mean[1]), float(mean[2]), float(mean[3])};
  return out;
}

// Float results of sums over thousands of samples: agree to 1e-5 relative.
void expect_same(const NodeResult& got, const NodeResult& want, int id) {
  auto tol = [](double v) { return 1e-5 * std::max(1.0, std::fabs(v)); };
  EXPECT_EQ(got.transparent, want.transparent) << id;
  EXPECT_NEAR(got.spatial, want.spatial, tol(want.spatial)) << id;
  EXPECT_NEAR(got.temporal, want.temporal, tol(want.temporal)) << id;
  EXPECT_NEAR(got.mean.r, want.mean.r, 1e-5) << id;
  EXPECT_NEAR(got.mean.g, want.mean.g, 1e-5) << id;
  EXPECT_NEAR(got.mean.b, want.mean.b, 1e-5) << id;
  EXPECT_NEAR(got.mean.a, want.mean.a, 1e-5) << id;
}

MemorySeries random_series(Dims d, int steps, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> noise(-1, 1);
  // Smooth in space and time plus noise, so nodes differ in mean, spread and change over time.
  return MemorySeries::generate(d, steps, [&](int t, int x, int y, int z) {
    return 10.0f + 3.0f * std::sin(0.2f * x + 0.3f * t) + 0.1f * y - 0.2f * z + noise(rng);
  });
}

TEST(ReferenceMetric, EqualsBruteForceTwoPassFormulas) {
  MemoryBrickStore store(random_series({21, 17, 12}, 5, 7), 8);
  const TransferFunction tf = test_tf(store.tree().value_range());
  ReferenceMetric ref(store);
  EXPECT_EQ(ref.update(tf, 2), store.tree().octree().brick_count());
  int transparent = 0;
  for (int id = 0; id < store.tree().size(); ++id) {
    const NodeResult want = brute_force(store, tf, id);
    transparent += want.transparent;
    expect_same(ref.node(id), want, id);
  }
  EXPECT_LT(transparent, store.tree().size());  // the test covers opaque nodes too
}

TEST(ReferenceMetric, TfDomainNarrowerThanTheDataClampsLikeTheBruteForce) {
  MemoryBrickStore store(random_series({9, 9, 9}, 4, 3), 8);
  const ValueRange r = store.tree().value_range();
  const TransferFunction tf = test_tf({r.lo + 0.3 * r.width(), r.hi - 0.3 * r.width()}, 32);
  ReferenceMetric ref(store);
  ref.update(tf, 1);
  for (int id = 0; id < store.tree().size(); ++id)
    expect_same(ref.node(id), brute_force(store, tf, id), id);
}

TEST(ReferenceMetric, EditRereadsOnlyBricksTouchingChangedEntries) {
  // Values rise with z by far more than the noise, so bricks along z own disjoint ranges.
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> noise(0, 1);
  auto series = MemorySeries::generate({15, 15, 29}, 4, [&](int, int, int, int z) {
    return float(std::min(z / 7, 3)) * 10.0f + noise(rng);  // z = 28 joins the last row
  });
  MemoryBrickStore store(series, 8);  // 2 × 2 × 4 bricks, brick row k holds values in [10k, 10k+1]
  const int bricks = store.tree().octree().brick_count();
  TransferFunction tf = test_tf({0, 40}, 40);  // one entry per unit
  ReferenceMetric ref(store);
  EXPECT_EQ(ref.update(tf), bricks);
  EXPECT_EQ(ref.update(tf), 0);    // nothing changed
  tf.set_entry(20, {1, 0, 0, 1});  // only the third row of bricks uses entry 20
  const std::int64_t reads_before = store.reads();
  EXPECT_EQ(ref.update(tf), bricks / 4);
  EXPECT_EQ(store.reads() - reads_before, bricks / 4 * store.tree().time().steps());
  tf.set_entry(35, {1, 1, 0, 1});  // no brick holds values in [35, 36)
  EXPECT_EQ(ref.update(tf), 0);
  // The incremental state equals a fresh computation.
  ReferenceMetric fresh(store);
  fresh.update(tf);
  for (int id = 0; id < store.tree().size(); ++id) expect_same(ref.node(id), fresh.node(id), id);
}

TEST(ReferenceMetric, ConstantDataHasZeroErrors) {
  auto series = MemorySeries::generate({12, 10, 9}, 3, [](int, int, int, int) { return 4.2f; });
  MemoryBrickStore store(series, 8, ValueRange{0, 10});
  TransferFunction tf = test_tf({0, 10}, 16);
  ReferenceMetric ref(store);
  ref.update(tf);
  for (int id = 0; id < store.tree().size(); ++id) {
    const NodeResult r = ref.node(id);
    EXPECT_FALSE(r.transparent);
    EXPECT_EQ(r.spatial, 0.0f) << id;
    EXPECT_EQ(r.temporal, 0.0f) << id;
    EXPECT_NEAR(r.mean.a, tf.lookup(4.2).a, 1e-6);
  }
}

TEST(ReferenceMetric, ReadFailurePropagatesAndTheNextUpdateStartsOver) {
  MemoryBrickStore store(random_series({9, 9, 9}, 3, 5), 8);
  TransferFunction tf = test_tf(store.tree().value_range(), 16);
  ReferenceMetric ref(store);
  store.fail_reads(true);
  EXPECT_THROW(ref.update(tf, 2), IoError);
  store.fail_reads(false);
  EXPECT_EQ(ref.update(tf, 2), store.tree().octree().brick_count());
  for (int id = 0; id < store.tree().size(); ++id)
    expect_same(ref.node(id), brute_force(store, tf, id), id);
}

}  // namespace
}  // namespace tsp

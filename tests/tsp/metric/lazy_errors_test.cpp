#include "tsp/metric/lazy_errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "support/memory_tree.h"
#include "tsp/core/error.h"
#include "tsp/metric/compute_errors.h"

namespace tsp {
namespace {

using tsptest::brute_force_tree;
using tsptest::MemorySeries;

TspTree test_tree() {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> noise(0, 1);
  // Values rise with x so octree nodes cover different parts of the TF domain.
  auto s = MemorySeries::generate({40, 9, 9}, 6, [&](int t, int x, int, int) {
    return 0.02f * x + 0.05f * t + 0.1f * noise(rng);
  });
  return brute_force_tree(s, 4);
}

TransferFunction ramp_tf(ValueRange d) {
  TransferFunction tf(d, 64);
  for (int j = 0; j < 64; ++j)
    tf.set_entry(j, {j / 63.f, 0.5f, 1 - j / 63.f, j < 8 ? 0.f : j / 63.f});
  return tf;
}

// Every node a traversal of step t may visit: per octree node, the time path to t's leaf.
std::set<int> step_nodes(const TspTree& tree, int t) {
  std::set<int> ids;
  for (int o = 0; o < tree.octree().size(); ++o)
    for (int tau = 0;; tau = tree.time().child_holding(tau, t)) {
      ids.insert(tree.id(o, tau));
      if (tree.time().is_leaf(tau)) break;
    }
  return ids;
}

void expect_matches_full(const TspTree& tree, const TransferFunction& tf, Metric m,
                         const NodeErrors& e, const std::set<int>& ids) {
  const MetricResult full = compute_errors(m, tree, tf, nullptr, 1);
  for (int id : ids) {
    EXPECT_FLOAT_EQ(e.spatial[id], full.errors.spatial[id]) << id;
    EXPECT_FLOAT_EQ(e.temporal[id], full.errors.temporal[id]) << id;
  }
}

TEST(LazyErrors, StepErrorsEqualTheWholeTreeComputation) {
  const TspTree tree = test_tree();
  TransferFunction tf = ramp_tf({0, 1.2});
  for (Metric m : {Metric::scalar, Metric::approximate, Metric::perceptual}) {
    LazyErrors lazy(tree, m, tf);
    const std::set<int> ids = step_nodes(tree, 3);
    const NodeErrors& e = lazy.errors_for_step(3);
    EXPECT_EQ(lazy.evaluations(), std::int64_t(ids.size()));  // exactly the visitable nodes
    expect_matches_full(tree, tf, m, e, ids);
    lazy.errors_for_step(3);
    EXPECT_EQ(lazy.evaluations(), std::int64_t(ids.size()));  // memoised
  }
}

TEST(LazyErrors, EditReevaluatesOnlyNodesTouchingTheChangedEntries) {
  const TspTree tree = test_tree();
  TransferFunction tf = ramp_tf({0, 1.2});
  for (Metric m : {Metric::approximate, Metric::perceptual}) {
    LazyErrors lazy(tree, m, tf);
    lazy.all(2);
    const std::int64_t before = lazy.evaluations();
    EXPECT_EQ(before, tree.size());
    // Change entries 40–41 only: nodes whose [j_min, j_max] misses them keep their results.
    std::vector<Rgba> edit(2, Rgba{1, 0, 0, 1});
    tf.set_entries(40, edit);
    int touching = 0;
    for (int id = 0; id < tree.size(); ++id) {
      const EntryRange r = entry_range(tf, tree.stats(id));
      touching += r.lo <= 41 && r.hi >= 40;
    }
    ASSERT_GT(touching, 0);
    ASSERT_LT(touching, tree.size());
    const NodeErrors& e = lazy.all(2);
    EXPECT_EQ(lazy.evaluations() - before, touching);
    std::set<int> every;
    for (int id = 0; id < tree.size(); ++id) every.insert(id);
    expect_matches_full(tree, tf, m, e, every);  // including e_t = e_st · V with the new V
    tf.set_entries(0, edit);  // a second edit: the step request catches up with both
    lazy.errors_for_step(0);
    expect_matches_full(tree, tf, m, lazy.errors_for_step(0), step_nodes(tree, 0));
  }
}

TEST(LazyErrors, NodeRequestsAndTfSwitch) {
  const TspTree tree = test_tree();
  TransferFunction a = ramp_tf({0, 1.2}), b({0, 1.2}, 64);  // b: fully transparent
  LazyErrors lazy(tree, Metric::approximate, a);
  EXPECT_FALSE(lazy.node(0).transparent);
  lazy.set_transfer_function(b);
  EXPECT_TRUE(lazy.node(0).transparent);
  EXPECT_EQ(lazy.node(0).spatial, 0.0f);
  EXPECT_EQ(lazy.evaluations(), 2);
  EXPECT_THROW(LazyErrors(tree, Metric::reference, a), UsageError);
}

}  // namespace
}  // namespace tsp

// Moments / NodeAccum: pairwise merging against direct two-pass formulas.
#include "tsp/tree/moments.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace tsp {
namespace {

struct Direct {
  double mean, m2;
};
Direct direct(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  const double mean = s / double(v.size());
  double m2 = 0;
  for (float x : v) m2 += (x - mean) * (x - mean);
  return {mean, m2};
}

TEST(Moments, MergingGroupsEqualsTheWholeInAnyOrder) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-3.f, 9.f);
  std::vector<float> all;
  std::vector<Moments> groups;
  for (int g = 0; g < 7; ++g) {
    Moments m;
    for (int i = 0; i < 10 + 13 * g; ++i) {
      float x = u(rng);
      all.push_back(x);
      m.add(x);
    }
    groups.push_back(m);
  }
  Moments forward, backward;
  for (const Moments& m : groups) forward.merge(m);
  for (auto it = groups.rbegin(); it != groups.rend(); ++it) backward.merge(*it);
  const Direct d = direct(all);
  for (const Moments* m : {&forward, &backward}) {
    EXPECT_EQ(m->n, double(all.size()));
    EXPECT_NEAR(m->mean, d.mean, 1e-12);
    EXPECT_NEAR(m->m2, d.m2, 1e-9);
    EXPECT_EQ(m->min, *std::min_element(all.begin(), all.end()));
    EXPECT_EQ(m->max, *std::max_element(all.begin(), all.end()));
  }
}

TEST(Moments, EmptyGroupsAreNeutral) {
  Moments a, empty;
  a.add(2.f);
  a.add(4.f);
  Moments b = a;
  b.merge(empty);
  EXPECT_EQ(b.n, 2);
  EXPECT_EQ(b.mean, 3);
  EXPECT_EQ(b.m2, 2);
  empty.merge(a);
  EXPECT_EQ(empty.mean, 3);
  EXPECT_EQ(empty.min, 2.f);
  EXPECT_EQ(Moments{}.std_dev(), 0);
}

TEST(Moments, LargeOffsetKeepsTheVariance) {
  // Values 1e8 + {0, 1, 2, 3}: variance 1.25; the naive Σv² − (Σv)²/N loses it in float.
  Moments m;
  for (int i = 0; i < 1000; ++i) m.add(float(1e8 + 8 * (i % 4)));  // float spacing at 1e8 is 8
  EXPECT_NEAR(m.std_dev(), 8 * std::sqrt(1.25), 1e-6);
}

TEST(NodeAccum, FinishAppliesTheCovRule) {
  NodeAccum a;
  a.moments.add(-2.f);
  a.moments.add(2.f);
  a.voxels = 2;
  a.cov_sum = 1.0;
  NodeStats s = a.finish(8.0);
  EXPECT_EQ(s.mean, 0);
  EXPECT_EQ(s.std, 2);
  EXPECT_FLOAT_EQ(s.spatial_error, 0.25f);  // zero mean: σ / range width
  EXPECT_FLOAT_EQ(s.temporal_error, 0.5f);  // cov_sum / voxels
  NodeAccum b;
  b.moments.add(-4.f);
  b.voxels = 1;
  a.merge(b);
  s = a.finish(8.0);
  EXPECT_EQ(a.voxels, 3);
  EXPECT_NEAR(s.mean, -4.0 / 3, 1e-15);
  EXPECT_NEAR(s.spatial_error, std::sqrt((4.0 / 9 + 100.0 / 9 + 64.0 / 9) / 3) / (4.0 / 3), 1e-6);
  EXPECT_EQ(NodeAccum{}.finish(1.0).spatial_error, 0);
}

}  // namespace
}  // namespace tsp

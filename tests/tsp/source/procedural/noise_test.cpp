#include "tsp/source/procedural/noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace tsp::noise {
namespace {

TEST(Noise, LatticeValuesAreInUnitIntervalAndRoughlyUniform) {
  const int kCount = 20000;
  double sum = 0;
  int low = 0;
  for (int i = 0; i < kCount; ++i) {
    float v = lattice(i % 37 - 18, i / 37, -i, 3, 42);
    ASSERT_GE(v, 0.0f);
    ASSERT_LT(v, 1.0f);
    sum += v;
    low += v < 0.25f;
  }
  // Uniform on [0,1): mean 0.5 ± ~0.002 (1σ), quarter below 0.25 ± ~0.003 (1σ).
  EXPECT_NEAR(sum / kCount, 0.5, 0.01);
  EXPECT_NEAR(double(low) / kCount, 0.25, 0.015);
}

TEST(Noise, HashDependsOnEveryCoordinateAndTheSeed) {
  const float base = lattice(1, 2, 3, 4, 5);
  EXPECT_NE(base, lattice(2, 1, 3, 4, 5));
  EXPECT_NE(base, lattice(1, 2, 4, 3, 5));
  EXPECT_NE(base, lattice(0, 2, 3, 4, 5));
  EXPECT_NE(base, lattice(1, 2, 3, 4, 6));
  EXPECT_EQ(base, lattice(1, 2, 3, 4, 5));
  EXPECT_EQ(lattice(7, -3, 9, 0, 11), unit_from_hash(hash_x(7, hash_yzw(-3, 9, 0, 11))));
}

TEST(Noise, FadeIsZeroAndOneAtEndsWithFlatSlopes) {
  EXPECT_EQ(fade(0.0f), 0.0f);
  EXPECT_EQ(fade(1.0f), 1.0f);
  EXPECT_NEAR(fade(0.5f), 0.5f, 1e-7);
  // Slope 30·h² near both ends: flat, so neighbouring cells join without a crease.
  const float h = 1e-2f;
  EXPECT_LT(fade(h) / h, 5e-3f);
  EXPECT_LT((1.0f - fade(1.0f - h)) / h, 5e-3f);
}

TEST(Noise, ValueAtLatticePointsIsTheLatticeValue) {
  for (int x = -3; x <= 3; ++x)
    for (int w = -2; w <= 2; ++w)
      EXPECT_EQ(value4(x, 5, -7, w, 99), lattice(x, 5, -7, w, 99)) << x << "," << w;
}

TEST(Noise, ValueIsInUnitIntervalAndContinuousAcrossCells) {
  for (int i = 0; i < 400; ++i) {
    double x = -5.0 + i * 0.0371, y = 0.3 * i, z = -1.7 + 0.011 * i, w = 0.05 * i;
    float v = value4(x, y, z, w, 3);
    ASSERT_GE(v, 0.0f);
    ASSERT_LT(v, 1.0f);
  }
  // Across the lattice plane x = 2 the value changes by O(ε) (the fade has zero slope there).
  for (double eps : {1e-3, 1e-5}) {
    float a = value4(2.0 - eps, 0.4, 0.7, 0.2, 8), b = value4(2.0 + eps, 0.4, 0.7, 0.2, 8);
    EXPECT_LT(std::fabs(a - b), 10 * eps);
  }
}

TEST(Noise, RowEvaluationMatchesPointEvaluationBitForBit) {
  const int n = 300;
  for (double dx : {0.013, 0.37, 1.9, -0.21}) {
    std::vector<float> row(n, 0.25f);
    const double x0 = -3.3, y = 1.25, z = -0.6, w = 2.75;
    const float amp = 0.5f;
    add_value4_row(row.data(), n, x0, dx, y, z, w, 17, amp);
    for (int i = 0; i < n; ++i)
      ASSERT_EQ(row[i], 0.25f + amp * value4(x0 + dx * i, y, z, w, 17))
          << "dx=" << dx << " i=" << i;
  }
}

}  // namespace
}  // namespace tsp::noise

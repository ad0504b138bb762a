// The online cost model against exact lines and a drifting intercept; its prediction error on
// noisy frames is reported.
#include "tsp/lod/cost_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace tsp {
namespace {

TEST(CostModel, RecoversAnExactLine) {
  CostModel m;
  EXPECT_FALSE(m.ready());
  for (int k = 0; k < 40; ++k) {
    const double cost = 1000 + 500 * (k % 7);
    m.add(cost, 12 + 0.02 * cost);
  }
  EXPECT_NEAR(m.slope(), 0.02, 1e-9);
  EXPECT_NEAR(m.intercept(), 12, 1e-6);
  EXPECT_NEAR(m.predict(5000), 112, 1e-5);
}

TEST(CostModel, BeforeTheSlopeIsIdentifiedHalfTheTimeIsFixed) {
  CostModel m;
  m.add(1000, 40);
  m.add(1000, 40);
  EXPECT_NEAR(m.predict(1000), 40, 1e-9);
  EXPECT_NEAR(m.slope(), 0.02, 1e-12);
  EXPECT_NEAR(m.intercept(), 20, 1e-9);
  m.add(-1, 5);  // ignored
  m.add(10, std::nan(""));
  EXPECT_NEAR(m.predict(1000), 40, 1e-9);
}

TEST(CostModel, FollowsAMovingInterceptAndReportsItsPredictionError) {
  CostModel m;
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0, 0.05);
  double err_sum = 0;
  int n = 0;
  for (int k = 0; k < 200; ++k) {
    const double a = k < 100 ? 10 : 25;  // a view change moves the fixed cost
    const double cost = 2000 + 1500 * std::sin(0.7 * k) * std::sin(0.7 * k);
    const double ms = (a + 0.01 * cost) * (1 + noise(rng));
    if (k > 20 && k != 100 && k != 101 && k != 102) {
      err_sum += std::fabs(m.predict(cost) - ms) / ms;
      ++n;
    }
    m.add(cost, ms);
  }
  const double mean_error = err_sum / n;
  std::printf("cost model: mean relative prediction error %.1f%% over %d frames (5%% noise)\n",
              100 * mean_error, n);
  EXPECT_LT(mean_error, 0.12);
  EXPECT_NEAR(m.intercept(), 25, 6);
}

}  // namespace
}  // namespace tsp

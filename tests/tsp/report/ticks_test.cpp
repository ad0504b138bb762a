// Round tick values (tsp/report/ticks.h) for the colour legends, against hand-computed ticks.
#include "tsp/report/ticks.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

TEST(Ticks, LegendTicksAreRoundNumbersInsideTheRange) {
  // A fitted range whose ends are not round: 0.2 0.4 0.6 0.8, not 0.0002 0.2501 … 0.9998.
  const std::vector<double> t = tsp::nice_ticks(0.0002, 0.9998, 6);
  ASSERT_EQ(t.size(), 4u);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(t[i], 0.2 * double(i + 1), 1e-12);
  EXPECT_EQ(tsp::tick_text(t[2], 0.2), "0.6");
  // Exact round ends are kept; steps of 2 and 5 × 10^k.
  EXPECT_EQ(tsp::nice_ticks(0, 1, 6), (std::vector<double>{0, 0.2, 0.4, 0.6, 0.8, 1.0}));
  const std::vector<double> big = tsp::nice_ticks(-3.7, 21.3, 6);
  EXPECT_EQ(big, (std::vector<double>{0, 5, 10, 15, 20}));
  EXPECT_EQ(tsp::tick_text(-1e-17, 5), "0");
  // Nothing round inside: the ends.
  EXPECT_EQ(tsp::nice_ticks(2, 2, 6), (std::vector<double>{2, 2}));
}

}  // namespace

// The vertical exaggeration a flat domain opens with, and how the picture names it.
#include "tsp/frame/exaggeration.h"

#include <gtest/gtest.h>

namespace tsp {
namespace {

Aabb box(double x, double y, double z) { return Aabb{{0, 0, 0}, {x, y, z}}; }

TEST(Exaggeration, FlatBoxesOpenStretchedByARoundNumber) {
  // WRF Katrina's T at its heights: 470 km × 470 km × 5.6 km: a third of 83.8 is 27.9 → 30.
  EXPECT_EQ(vertical_exaggeration(box(470e3, 470e3, 5610.5)), (std::array<double, 3>{1, 1, 30}));
  // 23 km wide, 700 m tall: 32.9 / 3 = 11 → 10; the larger horizontal edge counts.
  EXPECT_EQ(vertical_exaggeration(box(23e3, 5e3, 700)), (std::array<double, 3>{1, 1, 10}));
  EXPECT_EQ(vertical_exaggeration(box(5e3, 23e3, 700)), (std::array<double, 3>{1, 1, 10}));
  // Just flat (height under a tenth): 12 / 3 = 4 → 5 (nearer than 3 on a log scale).
  EXPECT_EQ(vertical_exaggeration(box(12, 1, 0.99)), (std::array<double, 3>{1, 1, 5}));
  // Very flat: at most 100.
  EXPECT_EQ(vertical_exaggeration(box(1e6, 1e6, 1)), (std::array<double, 3>{1, 1, 100}));
}

TEST(Exaggeration, OtherBoxesAreLeftAlone) {
  const std::array<double, 3> one{1, 1, 1};
  EXPECT_EQ(vertical_exaggeration(box(10, 10, 1)), one);  // exactly a tenth: not flat
  EXPECT_EQ(vertical_exaggeration(box(10, 10, 10)), one);
  EXPECT_EQ(vertical_exaggeration(box(1, 1, 100)), one);  // tall
  EXPECT_EQ(vertical_exaggeration(box(100, 100, 0)), one);  // one plane: nothing to stretch
  EXPECT_EQ(vertical_exaggeration(box(63, 6, 6)), one);    // a bar: as thin in y as in z
  EXPECT_EQ(vertical_exaggeration(empty_aabb()), one);
}

TEST(Exaggeration, TextNamesTheStretchedAxes) {
  EXPECT_EQ(exaggeration_text({1, 1, 30}), "z × 30");
  EXPECT_EQ(exaggeration_text({1, 1, 30}, true), "z x 30");
  EXPECT_EQ(exaggeration_text({2, 1, 0.5}), "x × 2, z × 0.5");
  EXPECT_EQ(exaggeration_text({1, 1, 1}), "");
}

}  // namespace
}  // namespace tsp

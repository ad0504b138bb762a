// Playing at a quality target without a window (player/rung_picker.h): from a tuned ladder the
// rung that keeps both the rate and the quality, the window's measured times correcting the
// probe's, keep quality or rate when none does both, a costlier rung only after the hold, and
// frames counted per rung.
#include "player/rung_picker.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using tspplayer::RungPicker;

// Full quality at 100 ms, a middle rung (ΔE 0.5) at 40 ms, a coarse one (ΔE 2) at 10 ms.
std::vector<tspgl::TunedRung> ladder() {
  std::vector<tspgl::TunedRung> t(3);
  t[0].mean_de = 0, t[0].ms = 100;
  t[1].mean_de = 0.5, t[1].ms = 40;
  t[2].mean_de = 2, t[2].ms = 10;
  return t;
}

TEST(PlayerRungPicker, KeepsRateAndQualityWithTheLeastError) {
  RungPicker p;
  p.choose(1, 5, true, 0, 0);  // no ladder yet: nothing
  EXPECT_EQ(p.choice().index, 0);
  p.set_ladder(ladder());
  p.choose(1, 5, true, 0, 0);  // 200 ms a step: full quality fits
  EXPECT_EQ(p.choice().index, 0);
  EXPECT_TRUE(p.choice().fits_rate);
  EXPECT_DOUBLE_EQ(p.choice().predicted_ms, 100);
  p.choose(1, 20, true, 0, 0.1);  // 50 ms a step: the middle rung (a new speed: at once)
  EXPECT_EQ(p.choice().index, 1);
  p.choose(1, 20, true, 20, 0.2);  // 20 ms outside rendering: 40 + 20 > 50, and the coarse
  EXPECT_EQ(p.choice().index, 1);   // rung misses the quality: keep quality keeps the middle
  EXPECT_FALSE(p.choice().fits_rate);
  EXPECT_TRUE(p.choice().within_quality);
  p.choose(1, 20, false, 20, 0.3);  // keep the rate: the coarse rung
  EXPECT_EQ(p.choice().index, 2);
  EXPECT_FALSE(p.choice().within_quality);
}

TEST(PlayerRungPicker, MeasuredTimesCorrectTheProbesAndACostlierRungWaitsForTheHold) {
  RungPicker p;
  p.set_ladder(ladder());
  p.choose(1, 20, true, 0, 0);
  ASSERT_EQ(p.choice().index, 1);
  // The window draws the middle rung at twice the probe's time: the ratio moves a fifth of the
  // way each frame (1.2, 1.36, ...) and the rung no longer fits 50 ms (40 × 1.36 > 50).
  p.measured(80);
  EXPECT_DOUBLE_EQ(p.time_ratio(), 1.2);
  p.measured(80);
  EXPECT_DOUBLE_EQ(p.time_ratio(), 1.36);
  EXPECT_EQ(p.frames(1), 2);
  EXPECT_EQ(p.frames(0), 0);
  p.choose(1, 20, false, 0, 0.5);  // keep the rate: the coarse rung, at once (cheaper)
  ASSERT_EQ(p.choice().index, 2);
  // Drawn much faster than probed (the ratio down to its floor, 0.25): even full quality fits
  // (100 × 0.25 = 25 ms), but it is costlier: not before kRungHoldSeconds after the last change.
  for (int k = 0; k < 40; ++k) p.measured(1);
  EXPECT_DOUBLE_EQ(p.time_ratio(), 0.25 + (1.36 - 0.25) * std::pow(0.8, 40));
  p.choose(1, 20, false, 0, 1.0);
  EXPECT_EQ(p.choice().index, 2);
  EXPECT_DOUBLE_EQ(p.choice().predicted_ms, 10 * p.time_ratio());
  p.choose(1, 20, false, 0, 1.6);
  EXPECT_EQ(p.choice().index, 0);
  // A new ladder starts over: its first rung, no frames.
  p.set_ladder(ladder());
  EXPECT_EQ(p.choice().index, 0);
  EXPECT_EQ(p.frames(2), 0);
}

}  // namespace

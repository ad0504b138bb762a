// The timeline's rate readout (src/player/rate_readout.h) on injected frame times, no clock: at
// 1 step/s with steps alternately 1.0 and 1.5 s apart (0.8 steps/s) it says "slower" steadily;
// the rule it replaced (2 s of steps, one threshold at 0.9) flipped between the two answers.
#include "player/rate_readout.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <vector>

namespace {

using namespace tspplayer;

// Steps shown at the given periods (repeated) for `seconds`, frames every frame_s: the readout's
// answers (slow or not) and rates after the first `settle` seconds.
struct Answers {
  int flips = 0;
  bool slow = false;
  double lo = 1e9, hi = 0;
};
Answers play(const std::vector<double>& periods, double speed, double seconds, double settle,
             double frame_s = 0.1) {
  RateReadout r;
  r.restart();
  Answers run;
  double next = 0;
  std::size_t k = 0;
  bool seen = false;
  for (int f = 0; f * frame_s <= seconds; ++f) {
    const double t = f * frame_s;
    const bool shown = t + 1e-9 >= next;
    if (shown) next += periods[k++ % periods.size()];
    r.frame(t, shown, speed);
    if (t < settle || !r.measured()) continue;
    if (seen && r.slow() != run.slow) ++run.flips;
    run.slow = r.slow();
    seen = true;
    run.lo = std::min(run.lo, r.rate());
    run.hi = std::max(run.hi, r.rate());
  }
  return run;
}

// The old rule on the same series: 2 s of shown steps, "slower" below 0.9 of the speed.
int old_flips(const std::vector<double>& periods, double speed, double seconds, double settle) {
  std::deque<double> at;
  double next = 0;
  std::size_t k = 0;
  int flips = 0, last = -1;
  for (int f = 0; f * 0.1 <= seconds; ++f) {
    const double t = f * 0.1;
    if (t + 1e-9 >= next) {
      at.push_back(t);
      next += periods[k++ % periods.size()];
    }
    while (at.size() > 2 && at.front() < t - 2) at.pop_front();
    if (t < settle || at.size() < 2) continue;
    const int slow = shown_rate(at, t) < 0.9 * speed;
    if (last >= 0 && slow != last) ++flips;
    last = slow;
  }
  return flips;
}

TEST(PlayerRateReadout, SaysOneSteadyThingAtAnUnevenSlowRate) {
  const std::vector<double> uneven{1.0, 1.5};  // 0.8 steps/s asked 1
  EXPECT_GT(old_flips(uneven, 1, 60, 6), 10);  // the flipping the walk saw
  const Answers r = play(uneven, 1, 60, 6);
  EXPECT_EQ(r.flips, 0);
  EXPECT_TRUE(r.slow);
  EXPECT_GE(r.lo, 0.7);
  EXPECT_LE(r.hi, 0.9);
}

TEST(PlayerRateReadout, OnTimeWithJitterStaysOnTime) {
  // 1 step/s with frames landing 0.9 to 1.1 s apart.
  const Answers r = play({1.0, 1.1, 0.9, 1.0}, 1, 60, 6);
  EXPECT_EQ(r.flips, 0);
  EXPECT_FALSE(r.slow);
  // 24 steps/s asked, 24 shown (a frame a step).
  const Answers fast = play({1.0 / 24}, 24, 20, 3, 1.0 / 24);
  EXPECT_EQ(fast.flips, 0);
  EXPECT_FALSE(fast.slow);
}

TEST(PlayerRateReadout, ARealSlowdownTurnsItOnceAndRestartForgets) {
  RateReadout r;
  double t = 0;
  for (; t < 10; t += 0.5) r.frame(t, true, 2);  // on time at 2 steps/s
  EXPECT_FALSE(r.slow());
  EXPECT_DOUBLE_EQ(r.rate(), 2);
  int flips = 0;
  bool was = r.slow();
  for (; t < 30; t += 1.0) {  // then 1 step/s
    r.frame(t, true, 2);
    flips += r.slow() != was;
    was = r.slow();
  }
  EXPECT_EQ(flips, 1);
  EXPECT_TRUE(r.slow());
  EXPECT_DOUBLE_EQ(r.rate(), 1);
  r.restart();
  EXPECT_FALSE(r.measured());
  EXPECT_FALSE(r.slow());
  EXPECT_EQ(r.rate(), 0);
}

// The printed rate: one decimal from 1 step/s on, two significant digits below (the eighth walk:
// playing at 0.25 steps/s read "0.3 shown/s").
TEST(PlayerRateReadout, RatesBelowOneKeepTwoSignificantDigits) {
  EXPECT_EQ(rate_text(24), "24.0");
  EXPECT_EQ(rate_text(9), "9.0");
  EXPECT_EQ(rate_text(1), "1.0");
  EXPECT_EQ(rate_text(0.999), "1.0");
  EXPECT_EQ(rate_text(0.8), "0.8");
  EXPECT_EQ(rate_text(0.25), "0.25");
  EXPECT_EQ(rate_text(0.5), "0.5");
  EXPECT_EQ(rate_text(0.04), "0.04");
  EXPECT_EQ(rate_text(0), "0");
}

}  // namespace

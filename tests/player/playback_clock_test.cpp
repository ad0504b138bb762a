// Playback's step clock (player/playback_clock.h) frame by frame, without a window: a step per
// period on time, one a frame with every step on however slow the frames, real time skipping
// steps only past the backlog, a stalled frame counting at most its cap, and the wait until the
// next step.
#include "player/playback_clock.h"

#include <gtest/gtest.h>

namespace {

using tspplayer::PlaybackClock;
using tspplayer::shown_rate;

TEST(PlayerPlaybackClock, OnTimeAStepAPeriod) {
  PlaybackClock c;
  EXPECT_EQ(c.advance(0.125, 4, true), 0);  // half a period
  EXPECT_DOUBLE_EQ(c.until_next(0, 4), 0.125);
  EXPECT_DOUBLE_EQ(c.until_next(0.0625, 4), 0.0625);
  EXPECT_DOUBLE_EQ(c.until_next(0.5, 4), 0);  // due
  EXPECT_EQ(c.advance(0.125, 4, true), 1);
  EXPECT_DOUBLE_EQ(c.ahead(), 0);
  for (int k = 0; k < 8; ++k) EXPECT_EQ(c.advance(0.25, 4, false), 1) << k;
}

TEST(PlayerPlaybackClock, EveryStepShowsOneAFrameRealTimeSkipsPastTheBacklog) {
  PlaybackClock every;
  EXPECT_EQ(every.advance(1.0, 4, true), 1);  // a 1 s frame at 4 steps/s: one step, no debt
  EXPECT_DOUBLE_EQ(every.ahead(), 0);
  PlaybackClock real;
  // 4 steps due: one shown, and one skipped to bring the clock back to 2 steps ahead.
  EXPECT_EQ(real.advance(1.0, 4, false), 2);
  EXPECT_DOUBLE_EQ(real.ahead(), 2);
  EXPECT_EQ(real.advance(0, 4, false), 1);  // then caught up by the next (fast) frames
  EXPECT_EQ(real.advance(0, 4, false), 1);
  EXPECT_EQ(real.advance(0, 4, false), 0);
  EXPECT_DOUBLE_EQ(real.ahead(), 0);
}

TEST(PlayerPlaybackClock, AStalledFrameCountsAtMostItsCapAndResetStartsAPeriodLater) {
  PlaybackClock c;
  EXPECT_EQ(c.advance(100, 4, false), 2);  // counted as 1 s: 4 steps due, as above
  PlaybackClock slow;
  EXPECT_EQ(slow.advance(100, 0.25, false), 1);  // at 0.25 steps/s: 1.5 periods (6 s)
  EXPECT_DOUBLE_EQ(slow.ahead(), 0.5);
  EXPECT_DOUBLE_EQ(slow.until_next(0, 0.25), 2);
  slow.reset();
  EXPECT_DOUBLE_EQ(slow.until_next(0, 0.25), 4);
}

// The rate over step periods: at 1 step/s, 0.9 s after the third step it is 1 (counted over the
// time since the first it read 2 / 2.9 = 0.7, "playing at 0.7 steps/s of 1"); a step on screen
// longer than the periods before reads as a slowing rate (3 steps over 4 s); one step: none.
TEST(PlayerPlaybackClock, TheShownRateCountsStepPeriodsNotTheTimeSinceTheLastStep) {
  EXPECT_DOUBLE_EQ(shown_rate({10, 11, 12}, 12.9), 1.0);
  EXPECT_DOUBLE_EQ(shown_rate({10, 11, 12}, 12.0), 1.0);
  EXPECT_DOUBLE_EQ(shown_rate({10, 11, 12}, 14.0), 0.75);
  EXPECT_DOUBLE_EQ(shown_rate({10, 10.5}, 10.9), 2.0);
  EXPECT_DOUBLE_EQ(shown_rate({10}, 11), 0.0);
  EXPECT_DOUBLE_EQ(shown_rate({}, 11), 0.0);
}

}  // namespace

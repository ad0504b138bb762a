// The player's playback tuning (src/player/playback_tuning.h): how a frame shares its time with
// the probe pictures, on injected times (no window, no clock). Playing, a picture is drawn only
// when it ends before the next step is due; a picture longer than any frame's room is drawn
// after kMaxTuningWaits step frames; still, a slice.
#include "player/playback_tuning.h"

#include <gtest/gtest.h>

namespace {

using namespace tspplayer;

TEST(PlayerPlaybackTuning, StillATuningTakesASliceAFrame) {
  TuningPace p;
  EXPECT_EQ(p.budget(false, 0, false, 500), kCalibrationSliceMs);
  EXPECT_FALSE(p.waiting());
}

TEST(PlayerPlaybackTuning, PlayingAPictureIsDrawnOnlyWhenItEndsBeforeTheNextStep) {
  TuningPace p;
  // The first picture's time is unknown: drawn (in the time left).
  EXPECT_EQ(p.budget(true, 90, true, -1), 90);
  // 40 ms predicted, 90 ms left before the next step: drawn, the budget the time left.
  EXPECT_EQ(p.budget(true, 90, true, 40), 90);
  EXPECT_FALSE(p.waiting());
  // 100 ms predicted, 90 left: none this frame; the window may sleep until the step.
  EXPECT_EQ(p.budget(true, 90, true, 100), 0);
  EXPECT_TRUE(p.waiting());
}

TEST(PlayerPlaybackTuning, APictureNoFrameHoldsIsDrawnAfterAFewStepFrames) {
  TuningPace p;
  int drawn_at = -1;
  for (int frame = 0; frame < 10 && drawn_at < 0; ++frame)
    if (p.budget(true, 100, true, 300) > 0) drawn_at = frame;
  EXPECT_EQ(drawn_at, kMaxTuningWaits);
  // Frames between steps (no new step) do not count towards it.
  TuningPace q;
  for (int frame = 0; frame < 20; ++frame) EXPECT_EQ(q.budget(true, 50, false, 300), 0);
  EXPECT_EQ(q.budget(true, 100, true, 300), 0);
  // A restart forgets the waits.
  q.restart();
  EXPECT_FALSE(q.waiting());
  for (int frame = 0; frame < kMaxTuningWaits; ++frame) EXPECT_EQ(q.budget(true, 100, true, 300), 0);
  EXPECT_GT(q.budget(true, 100, true, 300), 0);
}

}  // namespace

// The player's recorder: frames are due at the movie's rate from the start, a frame shown for a
// while is repeated for as long, and the movie lasts as long as the recording did.
#include <gtest/gtest.h>

#include <filesystem>

#include "player/recorder.h"
#include "support/paths.h"
#include "tsp/core/error.h"

namespace {

namespace fs = std::filesystem;
using tspplayer::frames_due;
using tspplayer::Recorder;

tsp::Image solid(int w, int h, std::uint8_t v) {
  tsp::Image im(w, h);
  for (std::size_t i = 0; i < im.rgba.size(); ++i) im.rgba[i] = (i % 4 == 3) ? 255 : v;
  return im;
}

TEST(Recorder, FramesAreDueAtTheMovieRateFromTheStart) {
  EXPECT_EQ(frames_due(10, 10, 25), 1);
  EXPECT_EQ(frames_due(10, 9, 25), 1);  // before the start: the start
  EXPECT_EQ(frames_due(10, 10.039, 25), 1);
  EXPECT_EQ(frames_due(10, 10.041, 25), 2);
  EXPECT_EQ(frames_due(0, 4, 25), 101);
  EXPECT_EQ(frames_due(0, 1, 8), 9);
}

TEST(Recorder, TheMovieLastsAsLongAsTheRecording) {
  TSPTEST_REQUIRE(std::system("command -v ffmpeg > /dev/null") == 0, "no ffmpeg");
  const fs::path out = tsptest::temp_dir() / "r.gif";
  constexpr int kFps = 25;
  Recorder r(out, 8, 6, kFps, 100.0);
  r.frame(solid(8, 6, 10), 100.0);   // 1 frame
  EXPECT_DOUBLE_EQ(r.seconds(), 1.0 / kFps);
  r.frame(solid(8, 6, 20), 100.5);   // shown 0.5 s after the start: frames up to it
  EXPECT_EQ(r.seconds(), double(frames_due(100.0, 100.5, kFps)) / kFps);
  r.frame(solid(8, 6, 30), 100.5);   // the same instant: nothing more is due
  EXPECT_EQ(r.seconds(), double(frames_due(100.0, 100.5, kFps)) / kFps);
  // Paused for 9.5 s: the last frame fills the tail, and the movie lasts 10 s.
  r.finish(110.0);
  EXPECT_DOUBLE_EQ(r.seconds(), 10.0);
  EXPECT_TRUE(fs::exists(out));
  // A frame of another size is refused (the view changed size).
  Recorder other(tsptest::temp_dir() / "s.gif", 8, 6, kFps, 0.0);
  EXPECT_THROW(other.frame(solid(4, 4, 1), 0.0), tsp::UsageError);
}

// A frame not fit for the movie (beyond the quality target) is not written: the last one that
// was is held for the wall-clock time instead; nothing is held before the first.
TEST(Recorder, HoldRepeatsTheLastFrameWritten) {
  TSPTEST_REQUIRE(std::system("command -v ffmpeg > /dev/null") == 0, "no ffmpeg");
  constexpr int kFps = 25;
  Recorder r(tsptest::temp_dir() / "h.gif", 8, 6, kFps, 0.0);
  r.hold(0.0);
  EXPECT_EQ(r.frames_held(), 0);
  EXPECT_EQ(r.seconds(), 0.0);
  r.frame(solid(8, 6, 10), 0.0);
  EXPECT_EQ(r.frames_shown(), 1);
  r.hold(1.0);  // a second of frames beyond the target: the first frame held
  EXPECT_EQ(r.frames_held(), frames_due(0, 1.0, kFps) - 1);
  EXPECT_EQ(r.frames_shown(), 1);
  r.frame(solid(8, 6, 20), 1.5);
  EXPECT_EQ(r.frames_shown() + r.frames_held(), frames_due(0, 1.5, kFps));
  r.finish(1.5);
}

}  // namespace

#include "player/playback_clock.h"

#include <algorithm>

namespace tspplayer {

namespace {
// A stalled frame does not skip many steps at once: a frame counts at most this long, or one and
// a half step periods at slow speeds (the window sleeps until a step is due, a period apart).
constexpr double kMaxFrameDt = 1.0, kMaxFramePeriods = 1.5;
// A frame shows the next step, not the one the clock has reached, while the clock is at most this
// many steps ahead: one slow frame among fast ones is caught up by the next frames instead of
// skipping a step; frames slower than the steps skip steps to keep time.
constexpr double kMaxStepBacklog = 2;
}  // namespace

int PlaybackClock::advance(double dt, double speed, bool every_step) {
  accum_ += std::min(dt, std::max(kMaxFrameDt, kMaxFramePeriods / speed)) * speed;
  // Every step: at most one step a frame, however slow the frames (no step is skipped).
  if (every_step) accum_ = std::min(accum_, 1.0);
  int advance = 0;
  if (accum_ >= 1) {
    advance = 1;
    accum_ -= 1;
  }
  if (accum_ > kMaxStepBacklog) {
    const int skip = int(accum_ - kMaxStepBacklog);
    advance += skip;
    accum_ -= skip;
  }
  return advance;
}

double PlaybackClock::until_next(double since_frame_s, double speed) const {
  const double pending = accum_ + since_frame_s * speed;
  return pending >= 1 ? 0.0 : (1 - pending) / std::max(speed, 1e-3);
}

}  // namespace tspplayer

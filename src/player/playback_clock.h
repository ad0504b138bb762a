// Playback's step clock (docs/player.md "Controls"): steps advance at the speed; with every
// step on at most one a frame (slower than the speed when frames are slow), else in real time,
// skipping steps once the clock is more than kMaxStepBacklog steps ahead (one slow frame among
// fast ones is caught up instead). Window-free: the caller passes each frame's seconds.
#pragma once

#include "player/rate_readout.h"  // (shown_rate, which lived here)

namespace tspplayer {

/// The clock's fraction of a step, from frame to frame.
class PlaybackClock {
 public:
  /// A frame of dt seconds at speed steps per second: the steps to move on (0, 1, or more in
  /// real time). A stalled frame counts at most kMaxFrameDt s (or 1.5 step periods at slow
  /// speeds). Never throws.
  int advance(double dt, double speed, bool every_step);
  /// Seconds until the next step is due, since_frame_s after the last advance (0: due now).
  /// Never throws.
  double until_next(double since_frame_s, double speed) const;
  /// Stopped: the next step comes a whole period after playback starts again.
  void reset() { accum_ = 0; }
  /// The steps the clock has run ahead of the step shown (fraction of one while on time).
  double ahead() const { return accum_; }

 private:
  double accum_ = 0;
};

}  // namespace tspplayer

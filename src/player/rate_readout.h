// The timeline's rate readout while playing (docs/player.md "Controls"): the steps shown per
// second and whether playback is slower than the speed asks ("playing at 0.8 steps/s of 1") or on
// time ("1.0 shown/s"), one steady answer. Counted over a window of at least kRateWindowPeriods
// step periods (two seconds held one period at 1 step/s: the rate was that period's), with
// hysteresis between the two texts (at 1 step/s with steps 1.0 and 1.5 s apart it flipped
// between "1.0 shown/s" and "playing at 0.7 of 1"). Window-free: the caller passes the times.
#pragma once
#include <deque>
#include <string>

namespace tspplayer {

/// Seconds of shown steps the rate is counted over, at least.
inline constexpr double kRateWindowSeconds = 2;
/// Step periods (at the speed asked) the rate is counted over, at least.
inline constexpr double kRateWindowPeriods = 5;
/// Playing every step, the readout turns to "slower" below this share of the speed...
inline constexpr double kSlowEnterShare = 0.85;
/// ...and back to "on time" only at or above this share.
inline constexpr double kSlowLeaveShare = 0.95;

/// Steps shown per second while playing, and whether that is slower than the speed.
class RateReadout {
 public:
  /// Playback started or stopped: nothing measured. Never throws.
  void restart();
  /// The frame at now_s showed a new step (shown) or not, at speed steps per second: updates the
  /// rate and the slow/on-time answer. Never throws but bad_alloc.
  void frame(double now_s, bool shown, double speed);
  /// True once a second step was shown since the restart (a rate was measured).
  bool measured() const { return shown_at_s_.size() >= 2; }
  /// Steps shown per second at the last frame (0 until measured()).
  double rate() const { return rate_; }
  /// True while the readout says playback is slower than the speed (with hysteresis).
  bool slow() const { return slow_; }

 private:
  std::deque<double> shown_at_s_;  ///< when each newly shown step was drawn, oldest first
  double rate_ = 0;
  bool slow_ = false;
};

/// A rate in steps per second as the readout prints it: one decimal from 1 on ("9.0", "1.0"), two
/// significant digits below ("0.25", "0.8": a speed of 0.25 read "0.3"). Never throws but
/// bad_alloc.
std::string rate_text(double steps_per_s);

/// Steps shown per second, from the times (s) at which each newly shown step was drawn (oldest
/// first) and the clock now: over the step periods between them (a step still on screen for
/// less than those periods took is no shortfall: counted over the time since the first, 1 step
/// a second read 0.7 between steps), or, once the step on screen has stayed longer than them,
/// over the time to now as if the next came now (a stall reads as a slowing rate). 0 with fewer
/// than two. Never throws.
double shown_rate(const std::deque<double>& shown_at_s, double now_s);

}  // namespace tspplayer

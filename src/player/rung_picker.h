// Playing at a quality target (docs/player.md "Playing at a quality target"): the tuned ladder
// and the rung each playing frame draws from it — re-chosen at once when the target, speed or
// rule changes or a cheaper rung is needed, a costlier one only with headroom and not straight
// after a change — corrected by the window's measured time per rung. Window- and GL-free (the
// tuning itself, jobs/playback_tuner.h, runs in the player), so tests feed it ladders and times.
#pragma once
#include <cstdint>
#include <vector>

#include "jobs/playback_tuner.h"

namespace tspplayer {

/// Smoothing, per frame, of the ratio of the window's render time to the probe's for a rung.
inline constexpr double kTimeRatioSmoothing = 0.2;
/// A rung costlier than the one playing is taken only when predicted within this share of the
/// step period, and kRungHoldSeconds after the last change (no flapping between two rungs).
inline constexpr double kRungHeadroom = 0.85;
/// See kRungHeadroom.
inline constexpr double kRungHoldSeconds = 1;

/// The tuned ladder and the rung playing draws.
class RungPicker {
 public:
  /// A new tuned ladder (tuned[0] full quality, or empty): its first rung, no frames counted.
  void set_ladder(std::vector<tspgl::TunedRung> tuned);
  /// The ladder (empty before the first tuning ends).
  const std::vector<tspgl::TunedRung>& ladder() const { return tuned_; }
  /// Chooses the rung the next playing frame draws at quality (mean ΔE > 0), speed (steps/s),
  /// keeping the quality or the rate, with overhead_ms outside rendering, at now_s (seconds).
  /// Nothing on an empty ladder. Never throws.
  void choose(double quality, double speed, bool keep_quality, double overhead_ms, double now_s);
  /// The window drew a frame with the chosen rung in render_ms: counted, and the time ratio
  /// corrected. Never throws.
  void measured(double render_ms);
  /// The rung chosen (index into ladder()).
  const tspgl::RungChoice& choice() const { return rung_; }
  /// Window render time over probe time, smoothed (1 at first).
  double time_ratio() const { return time_ratio_; }
  /// Frames drawn with ladder()[i] since the ladder was set.
  std::int64_t frames(std::size_t i) const { return i < frames_.size() ? frames_[i] : 0; }

 private:
  std::vector<tspgl::TunedRung> tuned_;
  tspgl::RungChoice rung_;
  std::vector<std::int64_t> frames_;
  double time_ratio_ = 1;
  double changed_s_ = -1e9;  // when the rung last changed
  // What the rung was chosen for: a change of any re-chooses at once.
  struct For {
    double quality = 0, speed = 0;
    bool keep_quality = true;
    bool operator==(const For&) const = default;
  } for_;
};

}  // namespace tspplayer

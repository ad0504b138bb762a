#include "player/rung_picker.h"

#include <algorithm>
#include <utility>

namespace tspplayer {

namespace {
// The ratio of window to probe time is kept within these bounds (one odd frame cannot swing it).
constexpr double kMinTimeRatio = 0.25, kMaxTimeRatio = 8;
}  // namespace

void RungPicker::set_ladder(std::vector<tspgl::TunedRung> tuned) {
  tuned_ = std::move(tuned);
  frames_.assign(tuned_.size(), 0);
  rung_ = {};
  for_ = {};
}

void RungPicker::choose(double quality, double speed, bool keep_quality, double overhead_ms,
                        double now_s) {
  if (tuned_.empty()) return;
  const double period_ms = 1000.0 / std::max(speed, 1e-3);
  const tspgl::RungChoice next =
      tspgl::choose_rung(tuned_, period_ms, time_ratio_, overhead_ms, quality, keep_quality);
  // A new target, speed or rule applies at once; otherwise a cheaper rung at once (the rate or
  // the quality is being missed) and a costlier one with headroom, not straight after a change.
  const For asked{quality, speed, keep_quality};
  const bool costlier = tuned_[std::size_t(next.index)].ms > tuned_[std::size_t(rung_.index)].ms;
  if (!(asked == for_) || !costlier ||
      (next.predicted_ms <= kRungHeadroom * period_ms && now_s - changed_s_ >= kRungHoldSeconds)) {
    if (next.index != rung_.index) changed_s_ = now_s;
    rung_ = next;
    for_ = asked;
    return;
  }
  // The same rung: its prediction with the current ratio.
  const tspgl::TunedRung& t = tuned_[std::size_t(rung_.index)];
  rung_.predicted_ms = t.ms * time_ratio_ + overhead_ms;
  rung_.fits_rate = rung_.predicted_ms <= period_ms;
  rung_.within_quality = t.mean_de <= tspgl::kPlaybackQualityMargin * quality;
}

void RungPicker::measured(double render_ms) {
  if (rung_.index >= int(tuned_.size())) return;
  ++frames_[std::size_t(rung_.index)];
  const double probe_ms = tuned_[std::size_t(rung_.index)].ms;
  if (probe_ms <= 0 || render_ms <= 0) return;
  const double ratio = std::clamp(render_ms / probe_ms, kMinTimeRatio, kMaxTimeRatio);
  time_ratio_ += kTimeRatioSmoothing * (ratio - time_ratio_);
}

}  // namespace tspplayer

#include "player/rate_readout.h"

#include <algorithm>
#include <cstdio>

namespace tspplayer {

void RateReadout::restart() {
  shown_at_s_.clear();
  rate_ = 0;
  slow_ = false;
}

void RateReadout::frame(double now_s, bool shown, double speed) {
  if (shown) shown_at_s_.push_back(now_s);
  // Several step periods at least (two seconds held one at 1 step/s). The last two stay: a
  // stall longer than the window reads as a slow rate, not none.
  const double window = std::max(kRateWindowSeconds, kRateWindowPeriods / std::max(speed, 1e-3));
  while (shown_at_s_.size() > 2 && shown_at_s_.front() < now_s - window) shown_at_s_.pop_front();
  rate_ = measured() ? shown_rate(shown_at_s_, now_s) : 0.0;
  if (!measured()) {
    slow_ = false;
    return;
  }
  // One answer until the rate clearly crosses to the other side.
  if (slow_ ? rate_ >= kSlowLeaveShare * speed : rate_ < kSlowEnterShare * speed) slow_ = !slow_;
}

double shown_rate(const std::deque<double>& shown_at_s, double now_s) {
  if (shown_at_s.size() < 2) return 0.0;
  const double n = double(shown_at_s.size());
  const double periods = shown_at_s.back() - shown_at_s.front();
  const double to_now = now_s - shown_at_s.front();
  if (!(periods > 0) || !(to_now > 0)) return 0.0;
  return std::min((n - 1) / periods, n / to_now);
}

std::string rate_text(double steps_per_s) {
  char text[32];
  // (Below 0.995 "%.1f" rounds: 0.25 to 0.3, 0.04 to 0.0.)
  std::snprintf(text, sizeof text, steps_per_s >= 0.995 ? "%.1f" : "%.2g", steps_per_s);
  return text;
}

}  // namespace tspplayer

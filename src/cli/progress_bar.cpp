#include "cli/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace tspcli {

namespace {
constexpr double kRedrawIntervalMs = 100;  // at most 10 redraws a second
constexpr int kBarWidth = 30;
constexpr double kMegabyte = 1e6;

}  // namespace

std::string clock_text(double seconds) {
  long s = std::lround(std::max(0.0, seconds));
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

ProgressBar::ProgressBar() : ProgressBar(stderr, isatty(STDERR_FILENO) == 1) {}

ProgressBar::ProgressBar(std::FILE* stream, bool enabled) : stream_(stream), enabled_(enabled) {}

ProgressBar::~ProgressBar() {
  finish();
}

std::string ProgressBar::format(const std::string& phase, std::int64_t done, std::int64_t total,
                                double seconds) {
  const double frac = total > 0 ? std::clamp(double(done) / double(total), 0.0, 1.0) : 1.0;
  const int filled = int(frac * kBarWidth);
  std::string bar(std::size_t(filled), '#');
  bar.resize(kBarWidth, '-');
  const double rate = seconds > 0 ? double(done) / seconds : 0;
  char buf[160];
  std::string eta = rate > 0 ? clock_text(double(total - done) / rate) : "--:--";
  std::snprintf(buf, sizeof buf, "%-8s [%s] %3d%%  %7.1f MB/s  ETA %s", phase.c_str(), bar.c_str(),
                int(frac * 100), rate / kMegabyte, eta.c_str());
  return buf;
}

void ProgressBar::update(const std::string& phase, std::int64_t done, std::int64_t total) {
  if (!enabled_) return;
  bool new_phase = phase != phase_;
  if (new_phase) {
    phase_ = phase;
    phase_watch_.restart();
  }
  if (!new_phase && done < total && redraw_watch_.ms() < kRedrawIntervalMs) return;
  redraw_watch_.restart();
  const double seconds = phase_watch_.seconds();
  std::fprintf(stream_, "\r%s\x1b[K", format(phase, done, total, seconds).c_str());
  std::fflush(stream_);
  drawn_ = true;
}

void ProgressBar::finish() {
  if (!drawn_) return;
  std::fprintf(stream_, "\r\x1b[K");
  std::fflush(stream_);
  drawn_ = false;
}

}  // namespace tspcli

// A one-line progress bar on stderr (phase, percent, MB/s, ETA), drawn only on a terminal.
#pragma once
#include "tsp/core/stopwatch.h"
#include <cstdint>
#include <cstdio>
#include <string>

namespace tspcli {

/// seconds as M:SS, or H:MM:SS from an hour on (negative: 0:00). Never throws.
std::string clock_text(double seconds);

/// Redraws at most 10 times a second; silent when the stream is not a TTY. Not thread-safe:
/// feed it from one thread at a time (the builder's progress callback is serialized).
class ProgressBar {
 public:
  /// A bar on stderr, enabled when stderr is a terminal.
  ProgressBar();
  /// A bar on stream, drawn only when enabled.
  ProgressBar(std::FILE* stream, bool enabled);
  /// Clears the line if anything was drawn.
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  /// Reports `done` of `total` bytes in phase; a new phase restarts the rate and ETA clocks.
  void update(const std::string& phase, std::int64_t done, std::int64_t total);
  /// Erases the bar so that normal output can follow.
  void finish();
  /// True when the bar draws anything.
  bool enabled() const { return enabled_; }

 private:
  static std::string format(const std::string& phase, std::int64_t done, std::int64_t total,
                            double seconds);
  std::FILE* stream_;
  bool enabled_;
  bool drawn_ = false;
  std::string phase_;
  tsp::Stopwatch phase_watch_;      ///< since the phase began
  tsp::Stopwatch redraw_watch_;     ///< since the last redraw
};

}  // namespace tspcli

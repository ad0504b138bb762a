// The one stopwatch of the project: a monotonic (steady_clock) timer for frame, build and
// benchmark timings.
#pragma once
#include <chrono>

namespace tsp {

/// Measures elapsed time from construction or the last restart() on the monotonic clock.
/// Never throws; one Stopwatch is not for concurrent restart() and reads.
class Stopwatch {
 public:
  using Clock = std::chrono::steady_clock;
  /// Starts timing now.
  Stopwatch() : start_(Clock::now()) {}
  /// Starts timing again from now.
  void restart() { start_ = Clock::now(); }
  /// Seconds since the start.
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  /// Milliseconds since the start.
  double ms() const { return seconds() * 1e3; }
  /// Milliseconds since the start, then restarts (for consecutive phases of one frame).
  double lap_ms() {
    const Clock::time_point now = Clock::now();
    const double out = std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
    return out;
  }

 private:
  Clock::time_point start_;
};

}  // namespace tsp

// The one stopwatch: monotonic, seconds and milliseconds agree, restart and lap start anew.
#include "tsp/core/stopwatch.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace {

using namespace std::chrono_literals;

TEST(Stopwatch, MeasuresAtLeastTheTimeSlept) {
  const tsp::Stopwatch w;
  std::this_thread::sleep_for(20ms);
  const double s = w.seconds(), ms = w.ms();
  EXPECT_GE(s, 0.020);
  EXPECT_GE(ms, 20.0);
  EXPECT_GE(ms, s * 1e3);  // read later, never smaller (monotonic clock)
}

TEST(Stopwatch, RestartAndLapStartFromNow) {
  tsp::Stopwatch w;
  std::this_thread::sleep_for(30ms);
  const double first = w.lap_ms();
  EXPECT_GE(first, 30.0);
  // Right after a lap the clock restarted: far less than the 30 ms just measured.
  EXPECT_LT(w.ms(), first);
  std::this_thread::sleep_for(5ms);
  w.restart();
  EXPECT_LT(w.ms(), 5.0 + first);
  EXPECT_GE(w.ms(), 0.0);
}

}  // namespace

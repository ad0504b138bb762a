// The build's step prefetcher: every step in order with the source's samples, the hook on the
// reading thread in step order, at most two steps read ahead of the consumer, and errors
// rethrown by next().
#include "tsp/build/step_prefetcher.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "support/memory_source.h"
#include "tsp/core/error.h"

namespace {

tsptest::MemorySource series(int steps) {
  return tsptest::MemorySource::from_function(
      {6, 5, 4}, steps, [](int x, int y, int z, int t) { return float(x + 10 * y + 100 * z + 1000 * t); });
}

TEST(StepPrefetcher, DeliversEveryStepInOrderAndHooksOnTheReaderThread) {
  tsptest::MemorySource src = series(7);
  std::vector<int> hooked;
  std::thread::id hook_thread;
  const std::thread::id me = std::this_thread::get_id();
  {
    tsp::StepPrefetcher p(src, [&](int t, const std::vector<float>& v, const std::vector<std::uint8_t>&) {
      hooked.push_back(t);
      hook_thread = std::this_thread::get_id();
      EXPECT_EQ(v[0], float(1000 * t));
    });
    for (int t = 0; t < 7; ++t) {
      const std::vector<float>& v = p.next();
      ASSERT_EQ(v.size(), std::size_t(src.dims().count()));
      EXPECT_EQ(v[5 + 6 * (4 + 5 * 3)], src.at(5, 4, 3, t)) << t;
      p.release();
    }
  }
  EXPECT_EQ(src.reads(), 7);
  EXPECT_EQ(hooked, (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_NE(hook_thread, me);
}

TEST(StepPrefetcher, SourceAndHookErrorsComeBackFromNext) {
  tsptest::MemorySource src = series(5);
  src.set_fail_at(2);
  tsp::StepPrefetcher p(src);
  p.next();
  p.release();
  p.next();
  p.release();
  EXPECT_THROW(p.next(), tsp::IoError);

  tsptest::MemorySource ok = series(3);
  tsp::StepPrefetcher q(ok, [](int t, const std::vector<float>&, const std::vector<std::uint8_t>&) {
    if (t == 1) throw tsp::FormatError("hook failed at step 1");
  });
  q.next();
  q.release();
  EXPECT_THROW(q.next(), tsp::FormatError);
}

TEST(StepPrefetcher, StopsEarlyWhenDestroyedMidSeries) {
  tsptest::MemorySource src = series(50);
  {
    tsp::StepPrefetcher p(src);
    p.next();  // never released: the reader fills the second buffer and waits
  }
  EXPECT_LE(src.reads(), 2);
}

}  // namespace

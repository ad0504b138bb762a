// The build's slab prefetcher: every step's planes in order, in slabs (read as slabs when the
// source can, else cut from whole steps), the hook on the reading thread once per read, at most
// one unit read ahead of the consumer, buffers reused once dropped, and errors rethrown by next().
#include "tsp/build/slab_prefetcher.h"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "support/memory_source.h"
#include "tsp/core/error.h"

namespace {

tsptest::MemorySource series(int steps) {
  return tsptest::MemorySource::from_function(
      {6, 5, 7}, steps, [](int x, int y, int z, int t) { return float(x + 10 * y + 100 * z + 1000 * t); });
}

// Reads every slab of steps 1, 3, 5 (first 1, stride 2) and checks each plane's samples.
void expect_every_plane(tsptest::MemorySource& src, bool slabs) {
  src.set_reads_slabs(slabs);
  std::vector<std::pair<int, int>> hooked;  // (step, z0) of each read
  std::thread::id hook_thread;
  {
    tsp::SlabPrefetcher p(
        src, 3,
        [&](const tsp::Slab& s) {
          hooked.emplace_back(s.step, s.z0);
          hook_thread = std::this_thread::get_id();
          EXPECT_EQ(s.plane(s.z0)[0], src.at(0, 0, s.z0, s.step));
        },
        1, 2);
    EXPECT_EQ(p.whole_steps(), !slabs);
    for (int t = 1; t < 7; t += 2)
      for (int z0 = 0; z0 < 7; z0 += 3) {
        const tsp::Slab s = p.next();
        ASSERT_EQ(s.step, t);
        ASSERT_EQ(s.z0, z0);
        ASSERT_EQ(s.z1, std::min(7, z0 + 3));
        for (int z = s.z0; z < s.z1; ++z) EXPECT_EQ(s.plane(z)[5 + 6 * 4], src.at(5, 4, z, t));
        EXPECT_EQ(s.mask_plane(z0), nullptr);
      }
  }
  const std::vector<std::pair<int, int>> want =
      slabs ? std::vector<std::pair<int, int>>{{1, 0}, {1, 3}, {1, 6}, {3, 0}, {3, 3}, {3, 6},
                                               {5, 0}, {5, 3}, {5, 6}}
            : std::vector<std::pair<int, int>>{{1, 0}, {3, 0}, {5, 0}};
  EXPECT_EQ(hooked, want);
  EXPECT_NE(hook_thread, std::this_thread::get_id());
}

TEST(SlabPrefetcher, DeliversEveryPlaneInOrderFromSlabReads) {
  tsptest::MemorySource src = series(7);
  expect_every_plane(src, true);
  EXPECT_EQ(src.reads(), 0);
  EXPECT_EQ(src.slab_reads(), 9);
}

TEST(SlabPrefetcher, CutsWholeStepsIntoSlabsWhenTheSourceCannotReadSlabs) {
  tsptest::MemorySource src = series(7);
  expect_every_plane(src, false);
  EXPECT_EQ(src.reads(), 3);
  EXPECT_EQ(src.slab_reads(), 0);
}

TEST(SlabPrefetcher, SourceAndHookErrorsComeBackFromNext) {
  tsptest::MemorySource src = series(5);
  src.set_fail_at(1);
  tsp::SlabPrefetcher p(src, 7);
  p.next();
  EXPECT_THROW(p.next(), tsp::IoError);

  tsptest::MemorySource ok = series(3);
  tsp::SlabPrefetcher q(ok, 7, [](const tsp::Slab& s) {
    if (s.step == 1) throw tsp::FormatError("hook failed at step 1");
  });
  q.next();
  EXPECT_THROW(q.next(), tsp::FormatError);
}

TEST(SlabPrefetcher, ReadsOneAheadAndStopsEarlyWhenDestroyed) {
  tsptest::MemorySource src = series(50);
  src.set_reads_slabs(true);
  {
    tsp::SlabPrefetcher p(src, 2);
    const tsp::Slab held = p.next();  // the reader reads one more slab and waits
    src.wait_for_slab_reads(2);        // (returns once the slab ahead has been read)
    EXPECT_EQ(src.slab_reads(), 2);
  }
  // Destroyed while its reader waited with the slab ahead: it stopped without reading on.
  EXPECT_EQ(src.slab_reads(), 2);
}

}  // namespace

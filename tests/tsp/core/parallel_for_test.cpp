// The one parallel-for: every index exactly once in chunks of the grain, per-worker state, the
// worker count, errors rethrown after every worker stopped, interruptions (SIGINT/SIGTERM) ending
// it within a chunk per worker, and empty ranges.
#include "tsp/core/parallel_for.h"

#include <gtest/gtest.h>

#include <signal.h>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "tsp/core/interrupt.h"

namespace {

using tsp::parallel_for;
using tsp::parallel_workers;

TEST(ParallelFor, EveryIndexOnceInChunksOfTheGrain) {
  for (int threads : {1, 2, 3, 8}) {
    for (std::int64_t n : {1, 7, 64, 1000}) {
      for (std::int64_t grain : {1, 3, 64, 5000}) {
        std::vector<std::atomic<int>> hits(static_cast<std::size_t>(n));
        std::mutex mu;
        std::set<std::pair<std::int64_t, std::int64_t>> chunks;
        parallel_for(n, grain, threads, [&](int worker, std::int64_t b, std::int64_t e) {
          EXPECT_GE(worker, 0);
          EXPECT_LT(worker, parallel_workers(n, grain, threads));
          for (auto i = b; i < e; ++i) ++hits[std::size_t(i)];
          std::lock_guard lock(mu);
          chunks.insert({b, e});
        });
        for (std::int64_t i = 0; i < n; ++i) ASSERT_EQ(hits[std::size_t(i)], 1) << i;
        // Chunks are [k·grain, min(n, (k+1)·grain)).
        std::int64_t expect = 0;
        for (auto [b, e] : chunks) {
          EXPECT_EQ(b, expect);
          EXPECT_EQ(e, std::min(n, b + grain));
          expect = e;
        }
        EXPECT_EQ(expect, n);
      }
    }
  }
}

TEST(ParallelFor, WorkerCountFollowsThreadsAndChunks) {
  EXPECT_EQ(parallel_workers(100, 10, 3), 3);
  EXPECT_EQ(parallel_workers(100, 50, 8), 2);  // two chunks
  EXPECT_EQ(parallel_workers(0, 1, 8), 1);
  EXPECT_EQ(parallel_workers(5, 1, 1), 1);
  EXPECT_EQ(tsp::resolve_threads(4), 4);
  EXPECT_GE(tsp::resolve_threads(0), 1);
  EXPECT_EQ(tsp::resolve_threads(0), tsp::resolve_threads(-3));
}

TEST(ParallelFor, PerWorkerStateNeedsNoLock) {
  const std::int64_t n = 10000;
  const int threads = 4;
  std::vector<std::int64_t> sums(std::size_t(parallel_workers(n, 16, threads)), 0);
  std::vector<std::thread::id> owner(sums.size());
  std::mutex mu;
  parallel_for(n, 16, threads, [&](int w, std::int64_t b, std::int64_t e) {
    {
      std::lock_guard lock(mu);
      // One worker index is always the same thread.
      if (owner[std::size_t(w)] == std::thread::id()) owner[std::size_t(w)] = std::this_thread::get_id();
      EXPECT_EQ(owner[std::size_t(w)], std::this_thread::get_id());
    }
    for (auto i = b; i < e; ++i) sums[std::size_t(w)] += i;
  });
  std::int64_t total = 0;
  for (auto s : sums) total += s;
  EXPECT_EQ(total, n * (n - 1) / 2);
  // Worker 0 is the calling thread (when it got a chunk at all).
  if (owner[0] != std::thread::id()) {
    EXPECT_EQ(owner[0], std::this_thread::get_id());
  }
}

TEST(ParallelFor, FirstErrorIsRethrownAndLaterChunksDoNotStart) {
  // One worker: chunks 0 … 10 ran, chunk 10 threw, nothing after it started.
  std::atomic<int> ran{0};
  try {
    parallel_for(200, 1, 1, [&](int, std::int64_t b, std::int64_t) {
      ++ran;
      if (b == 10) throw std::runtime_error("chunk 10 failed");
    });
    ADD_FAILURE() << "no error rethrown";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "chunk 10 failed");
  }
  EXPECT_EQ(ran.load(), 11);
  // Three workers: the only error is rethrown, after every chunk up to it ran. How many later
  // chunks the others start before the failing worker has recorded its error depends on the
  // scheduler (trivial chunks can outrun the unwinding), so it is not asserted here; stopping
  // within one chunk per worker is asserted by the interruption test below, whose flag is set
  // before any waiting chunk goes on.
  ran = 0;
  std::atomic<bool> reached{false};
  EXPECT_THROW(parallel_for(200, 1, 3,
                            [&](int, std::int64_t b, std::int64_t) {
                              ++ran;
                              if (b == 10) {
                                reached = true;
                                throw std::runtime_error("chunk 10 failed");
                              }
                            }),
               std::runtime_error);
  EXPECT_TRUE(reached.load());
  EXPECT_GE(ran.load(), 11);
}

TEST(ParallelFor, AnInterruptionStopsItWithinOneChunkPerWorker) {
  for (int threads : {1, 3}) {
    std::atomic<int> ran{0};
    EXPECT_THROW(parallel_for(200, 1, threads,
                              [&](int, std::int64_t b, std::int64_t) {
                                ++ran;
                                if (b == 10) tsp::detail::simulate_interrupt(SIGTERM);
                                while (b > 10 && !tsp::interrupted()) std::this_thread::yield();
                              }),
                 tsp::Interrupted);
    tsp::detail::clear_interrupt();
    // Chunks 0..10, and at most one more already started by each other worker.
    EXPECT_GE(ran.load(), 11);
    EXPECT_LE(ran.load(), 10 + threads);
  }
}

TEST(ParallelFor, EmptyRangeCallsNothing) {
  bool called = false;
  parallel_for(0, 4, 4, [&](int, std::int64_t, std::int64_t) { called = true; });
  parallel_for(-5, 4, 4, [&](int, std::int64_t, std::int64_t) { called = true; });
  EXPECT_FALSE(called);
}

}  // namespace

#include "tsp/store/brick_cache.h"

#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <future>
#include <mutex>
#include <random>
#include <thread>
#include <vector>

#include "support/memory_tree.h"
#include "tsp/core/error.h"

namespace tsp {
namespace {

using tsptest::MemoryBrickStore;
using tsptest::MemorySeries;

// 29 × 15 × 8 samples with 8-sample bricks: 4 × 2 × 1 bricks, all 8³ samples (1024 bytes).
constexpr Dims kDims{29, 15, 8};
constexpr int kSteps = 5;
constexpr int kBricks = 8;
constexpr std::int64_t kEntry = 8 * 8 * 8 * 2;

MemoryBrickStore make_store() {
  return MemoryBrickStore(MemorySeries::uniform(kDims, kSteps, 17, -4, 9), 8);
}

std::vector<std::uint16_t> direct(const BrickStore& store, int brick, int step) {
  std::vector<std::uint16_t> v(store.tree().octree().brick_samples(brick).count());
  store.read_brick(brick, step, v);
  return v;
}

// A store that blocks every read until open() and tells when a read has started.
class GatedStore : public BrickStore {
 public:
  explicit GatedStore(const BrickStore& inner) : inner_(inner) {}
  const TspTree& tree() const override { return inner_.tree(); }
  void read_brick(int brick, int step, std::span<std::uint16_t> out) const override {
    std::unique_lock lock(mu_);
    ++started_;
    cv_.notify_all();
    cv_.wait(lock, [&] { return open_; });
    lock.unlock();
    inner_.read_brick(brick, step, out);
  }
  void wait_started(int n) const {
    std::unique_lock lock(mu_);
    cv_.wait(lock, [&] { return started_ >= n; });
  }
  void open() {
    std::lock_guard lock(mu_);
    open_ = true;
    cv_.notify_all();
  }
  int started() const {
    std::lock_guard lock(mu_);
    return started_;
  }

 private:
  const BrickStore& inner_;
  mutable std::mutex mu_;
  mutable std::condition_variable cv_;
  mutable int started_ = 0;
  bool open_ = false;
};

TEST(BrickCache, ValuesEqualTheStoresAndRepeatedGetsHit) {
  MemoryBrickStore store = make_store();
  ASSERT_EQ(store.tree().octree().brick_count(), kBricks);
  BrickCache cache(store, kBricks * kSteps * kEntry);
  EXPECT_EQ(cache.entry_bytes(3), kEntry);
  for (int b = 0; b < kBricks; ++b)
    for (int t = 0; t < kSteps; ++t) {
      const BrickSamples s = cache.get(b, t);
      ASSERT_TRUE(s);
      EXPECT_EQ(*s, direct(store, b, t)) << b << " " << t;
    }
  const std::int64_t reads = store.reads();
  for (int t = 0; t < kSteps; ++t) EXPECT_EQ(*cache.get(5, t), direct(store, 5, t));
  EXPECT_EQ(store.reads(), reads + kSteps);  // only the direct() reads
  const BrickCacheStats s = cache.stats();
  EXPECT_EQ(s.misses, kBricks * kSteps);
  EXPECT_EQ(s.hits, kSteps);
  EXPECT_EQ(s.bytes_read, kBricks * kSteps * kEntry);
  EXPECT_EQ(s.resident_count, kBricks * kSteps);
  EXPECT_EQ(s.resident_bytes, kBricks * kSteps * kEntry);
  EXPECT_EQ(s.evictions, 0);
}

TEST(BrickCache, EvictsLeastRecentlyUsedWithinItsBudget) {
  MemoryBrickStore store = make_store();
  BrickCache cache(store, 3 * kEntry + kEntry / 2);
  cache.get(0, 0);
  cache.get(1, 0);
  cache.get(2, 0);
  cache.get(0, 0);  // (1, 0) is now the least recently used
  cache.get(3, 0);
  EXPECT_TRUE(cache.contains(0, 0));
  EXPECT_FALSE(cache.contains(1, 0));
  EXPECT_TRUE(cache.contains(2, 0));
  EXPECT_TRUE(cache.contains(3, 0));
  cache.get(4, 1);
  EXPECT_FALSE(cache.contains(2, 0));
  const BrickCacheStats s = cache.stats();
  EXPECT_EQ(s.evictions, 2);
  EXPECT_EQ(s.resident_count, 3);
  EXPECT_EQ(s.resident_bytes, 3 * kEntry);
  EXPECT_EQ(s.hits, 1);
  EXPECT_EQ(s.misses, 5);
}

TEST(BrickCache, BrickLargerThanTheBudgetIsReturnedButNotKept) {
  MemoryBrickStore store = make_store();
  BrickCache cache(store, kEntry - 1);
  const BrickSamples s = cache.get(6, 2);
  EXPECT_EQ(*s, direct(store, 6, 2));
  EXPECT_FALSE(cache.contains(6, 2));
  EXPECT_EQ(cache.stats().resident_bytes, 0);
  BrickCache none(store, 0);
  EXPECT_EQ(*none.get(1, 1), direct(store, 1, 1));
}

TEST(BrickCache, EvictedSamplesStayValidForTheirHolders) {
  MemoryBrickStore store = make_store();
  BrickCache cache(store, kEntry);
  const BrickSamples first = cache.get(0, 0);
  cache.get(1, 0);
  EXPECT_FALSE(cache.contains(0, 0));
  EXPECT_EQ(*first, direct(store, 0, 0));
  cache.clear();
  EXPECT_EQ(cache.stats().resident_count, 0);
  EXPECT_FALSE(cache.contains(1, 0));
}

TEST(BrickCache, ReadFailureCachesNothingAndLaterGetsRetry) {
  MemoryBrickStore store = make_store();
  BrickCache cache(store, 10 * kEntry);
  store.fail_reads(true);
  EXPECT_THROW(cache.get(2, 3), IoError);
  EXPECT_FALSE(cache.contains(2, 3));
  EXPECT_EQ(cache.stats().resident_count, 0);
  EXPECT_EQ(cache.stats().bytes_read, 0);
  store.fail_reads(false);
  EXPECT_EQ(*cache.get(2, 3), direct(store, 2, 3));
}

TEST(BrickCache, NegativeBudgetIsAUsageError) {
  MemoryBrickStore store = make_store();
  EXPECT_THROW(BrickCache(store, -1), UsageError);
}

TEST(BrickCache, PrefetchLoadsInOrderUpToTheBudget) {
  MemoryBrickStore store = make_store();
  BrickCache cache(store, 3 * kEntry);
  cache.get(1, 1);
  const std::vector<BrickKey> keys = {{1, 1}, {2, 1}, {3, 1}, {4, 1}, {5, 1}, {6, 1}};
  EXPECT_EQ(cache.prefetch(keys), 3);  // (1,1) is resident; 2, 3, 4 fill one budget
  EXPECT_TRUE(cache.contains(2, 1));
  EXPECT_TRUE(cache.contains(3, 1));
  EXPECT_TRUE(cache.contains(4, 1));
  EXPECT_FALSE(cache.contains(5, 1));
  EXPECT_FALSE(cache.contains(1, 1));  // evicted by the prefetch: it was least recently used
  BrickCacheStats s = cache.stats();
  EXPECT_EQ(s.prefetched, 3);
  EXPECT_EQ(s.misses, 1);
  EXPECT_EQ(s.bytes_read, 4 * kEntry);
  EXPECT_EQ(*cache.get(3, 1), direct(store, 3, 1));
  EXPECT_EQ(cache.stats().hits, 1);
  store.fail_reads(true);
  const std::vector<BrickKey> more = {{0, 4}};
  EXPECT_THROW(cache.prefetch(more), IoError);
}

TEST(BrickCache, ConcurrentGetsOfOneMissingBrickReadItOnce) {
  MemoryBrickStore store = make_store();
  GatedStore gated(store);
  BrickCache cache(gated, 10 * kEntry);
  constexpr int kThreads = 6;
  std::vector<std::future<BrickSamples>> results;
  results.push_back(std::async(std::launch::async, [&] { return cache.get(7, 4); }));
  gated.wait_started(1);  // the first get is inside read_brick; the others must wait for it
  for (int i = 1; i < kThreads; ++i)
    results.push_back(std::async(std::launch::async, [&] { return cache.get(7, 4); }));
  // Every other get has found the read in progress (a latch on the cache's count, no sleep).
  while (cache.stats().waited < kThreads - 1) std::this_thread::yield();
  gated.open();
  const std::vector<std::uint16_t> want = direct(store, 7, 4);
  for (auto& r : results) EXPECT_EQ(*r.get(), want);
  EXPECT_EQ(gated.started(), 1);
  const BrickCacheStats s = cache.stats();
  EXPECT_EQ(s.misses, 1);
  EXPECT_EQ(s.hits, kThreads - 1);
  EXPECT_EQ(s.waited, kThreads - 1);
  EXPECT_EQ(s.bytes_read, kEntry);
}

TEST(BrickCache, WaitersOfAFailingReadGetItsError) {
  MemoryBrickStore store = make_store();
  GatedStore gated(store);
  BrickCache cache(gated, 10 * kEntry);
  store.fail_reads(true);
  std::vector<std::future<BrickSamples>> results;
  results.push_back(std::async(std::launch::async, [&] { return cache.get(3, 2); }));
  gated.wait_started(1);
  for (int i = 0; i < 3; ++i)
    results.push_back(std::async(std::launch::async, [&] { return cache.get(3, 2); }));
  while (cache.stats().waited < 3) std::this_thread::yield();  // all three wait on the read
  gated.open();
  for (auto& r : results) EXPECT_THROW(r.get(), IoError);
  EXPECT_FALSE(cache.contains(3, 2));
  store.fail_reads(false);
  EXPECT_EQ(*cache.get(3, 2), direct(store, 3, 2));
}

TEST(BrickCache, ConcurrentRandomGetsReturnTheStoresValues) {
  MemoryBrickStore store = make_store();
  std::vector<std::vector<std::uint16_t>> want;
  for (int b = 0; b < kBricks; ++b)
    for (int t = 0; t < kSteps; ++t) want.push_back(direct(store, b, t));
  const std::int64_t reads_before = store.reads();
  BrickCache cache(store, 11 * kEntry);  // about a quarter of the 40 entries
  constexpr int kThreads = 8, kGets = 3000;
  std::atomic<int> wrong{0};
  std::vector<std::thread> threads;
  for (int i = 0; i < kThreads; ++i)
    threads.emplace_back([&, i] {
      std::mt19937 rng(100 + i);
      std::uniform_int_distribution<int> b(0, kBricks - 1), t(0, kSteps - 1);
      for (int g = 0; g < kGets; ++g) {
        const int bi = b(rng), ti = t(rng);
        if (g % 500 == 0) {
          const std::vector<BrickKey> keys = {{bi, ti}, {(bi + 1) % kBricks, ti}};
          cache.prefetch(keys);
        }
        if (*cache.get(bi, ti) != want[bi * kSteps + ti]) ++wrong;
      }
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(wrong, 0);
  const BrickCacheStats s = cache.stats();
  EXPECT_EQ(s.hits + s.misses, kThreads * kGets);
  EXPECT_GT(s.hits, 0);
  EXPECT_GT(s.evictions, 0);
  EXPECT_EQ(store.reads() - reads_before, s.misses + s.prefetched);
  EXPECT_EQ(s.bytes_read, (s.misses + s.prefetched) * kEntry);
  EXPECT_LE(s.resident_bytes, cache.budget());
  EXPECT_EQ(s.resident_bytes, s.resident_count * kEntry);
}

}  // namespace
}  // namespace tsp

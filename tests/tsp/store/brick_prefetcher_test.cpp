#include "tsp/store/brick_prefetcher.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "support/memory_tree.h"
#include "tsp/core/error.h"

namespace tsp {
namespace {

constexpr std::int64_t kBudget = std::int64_t(1) << 20;
constexpr int kSteps = 5;
// 29 × 15 × 8 samples with 8-sample bricks: 4 × 2 × 1 = 8 bricks of 8³ samples.
constexpr Dims kDims{29, 15, 8};
constexpr int kBricks = 8;

using tsptest::MemoryBrickStore;
using tsptest::MemorySeries;

MemoryBrickStore make_store() {
  return MemoryBrickStore(MemorySeries::uniform(kDims, kSteps, 5, 0, 1), 8);
}

std::vector<BrickKey> all_bricks(int step) {
  std::vector<BrickKey> keys;
  for (int b = 0; b < kBricks; ++b) keys.push_back({b, step});
  return keys;
}

TEST(BrickPrefetcher, ReadsRequestedBricksSoLaterGetsHitWithTheSameSamples) {
  MemoryBrickStore store = make_store();
  BrickCache cache(store, kBudget);
  BrickPrefetcher prefetcher(cache);
  prefetcher.request(all_bricks(3));
  prefetcher.wait_idle();
  EXPECT_EQ(prefetcher.bricks_read(), kBricks);
  EXPECT_EQ(store.reads(), kBricks);
  for (int b = 0; b < kBricks; ++b) {
    BrickSamples s = cache.get(b, 3);
    std::vector<std::uint16_t> direct(s->size());
    store.read_brick(b, 3, direct);
    EXPECT_EQ(*s, direct) << "brick " << b;
  }
  EXPECT_EQ(cache.stats().hits, kBricks);
  EXPECT_EQ(cache.stats().misses, 0);
  // Requesting cached bricks again reads nothing.
  prefetcher.request(all_bricks(3));
  prefetcher.wait_idle();
  EXPECT_EQ(store.reads(), 2 * kBricks);  // the direct reads above
  EXPECT_EQ(prefetcher.bricks_read(), kBricks);
}

TEST(BrickPrefetcher, ANewRequestIsReadAfterAnEarlierOneAndEmptyRequestsAreIdle) {
  MemoryBrickStore store = make_store();
  BrickCache cache(store, kBudget);
  BrickPrefetcher prefetcher(cache);
  prefetcher.wait_idle();  // nothing requested: returns at once
  prefetcher.request(all_bricks(0));
  prefetcher.request(all_bricks(1));  // replaces what is left of step 0
  prefetcher.wait_idle();
  for (int b = 0; b < kBricks; ++b) EXPECT_TRUE(cache.contains(b, 1)) << b;
  // Step 0 was at most partly read (whatever the worker took before the replacement).
  EXPECT_EQ(prefetcher.bricks_read(), store.reads());
  EXPECT_GE(prefetcher.bricks_read(), kBricks);
}

TEST(BrickPrefetcher, ReadErrorsAreKeptNotThrownAndTheWorkerGoesOn) {
  MemoryBrickStore store = make_store();
  BrickCache cache(store, kBudget);
  BrickPrefetcher prefetcher(cache);
  store.fail_reads(true);
  prefetcher.request(all_bricks(2));
  prefetcher.wait_idle();
  EXPECT_FALSE(prefetcher.last_error().empty());
  EXPECT_EQ(prefetcher.bricks_read(), 0);
  store.fail_reads(false);
  prefetcher.request(all_bricks(4));
  prefetcher.wait_idle();
  EXPECT_EQ(prefetcher.bricks_read(), kBricks);
}

}  // namespace
}  // namespace tsp

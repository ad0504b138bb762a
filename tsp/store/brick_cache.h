// RAM cache of quantized brick samples read from a BrickStore (a .tsp file), keyed by
// (brick, step), with its own byte budget and LRU eviction. Thread-safe. See docs/caching.md.
#pragma once
#include <cstddef>
#include <cstdint>
#include <future>
#include <list>
#include <memory>
#include <mutex>
#include <span>
#include <unordered_map>
#include <vector>

#include "tsp/store/brick_store.h"

namespace tsp {

/// One brick at one step.
struct BrickKey {
  int brick = 0;
  int step = 0;
  bool operator==(const BrickKey&) const = default;
};

/// Immutable samples of one brick at one step (lattice(b).count() codes, x fastest; then, when
/// the tree has a stencil, as many inside flags, 0 or 1).
/// Holders keep them alive after the cache has evicted them.
using BrickSamples = std::shared_ptr<const std::vector<std::uint16_t>>;

/// Counters since construction (or since the last clear() for the resident ones).
struct BrickCacheStats {
  std::int64_t hits = 0;        ///< get() served without reading the store
  std::int64_t waited = 0;      ///< of the hits, get() that waited for another's read of the key
  std::int64_t misses = 0;      ///< get() that read the store
  std::int64_t prefetched = 0;  ///< bricks read by prefetch()
  std::int64_t bytes_read = 0;  ///< bytes read from the store (misses and prefetches)
  std::int64_t evictions = 0;   ///< entries evicted to meet the budget
  std::int64_t resident_count = 0;
  std::int64_t resident_bytes = 0;
};

/// LRU cache of brick samples in RAM within a byte budget (2 bytes per sample). get(),
/// contains(), prefetch(), stats() and clear() may be called from any thread at once; the store
/// is read outside the lock, and concurrent get()s of the same missing key read it once.
class BrickCache {
 public:
  /// A cache over store (which must outlive it and have a thread-safe read_brick) holding at
  /// most budget_bytes (≥ 0) of samples. Throws UsageError on a negative budget.
  BrickCache(const BrickStore& store, std::int64_t budget_bytes);

  /// Samples of brick at step, read from the store on a miss and made most recently used. A
  /// brick larger than the whole budget is returned but not kept. Asserts the key is in range;
  /// throws what the store's read_brick throws (nothing is cached then).
  BrickSamples get(int brick, int step);
  /// True when (brick, step) is resident.
  bool contains(int brick, int step) const;
  /// Reads the keys not yet resident, in the given order (most wanted first), and stops once
  /// the bytes it read would exceed the budget (later keys would evict earlier ones). Meant to be
  /// called from a player's background thread; this class starts no thread. Returns the number
  /// of bricks read; throws what the store throws (keys read before stay cached).
  int prefetch(std::span<const BrickKey> keys);
  /// Drops every resident entry (samples held by callers stay valid).
  void clear();

  /// Counters.
  BrickCacheStats stats() const;
  /// Byte budget.
  std::int64_t budget() const { return budget_; }
  /// The store it reads from.
  const BrickStore& store() const { return store_; }
  /// Bytes of one (brick, step) entry: its stored sample count × 2.
  std::int64_t entry_bytes(int brick) const;

 private:
  struct KeyHash {
    std::size_t operator()(const BrickKey& k) const;
  };
  struct Entry {
    BrickKey key;
    BrickSamples samples;
    std::int64_t bytes = 0;
  };
  using List = std::list<Entry>;  // front = most recently used

  const BrickStore& store_;
  const std::int64_t budget_;
  mutable std::mutex mu_;
  List lru_;
  std::unordered_map<BrickKey, List::iterator, KeyHash> index_;
  // Reads in progress, so a second get() of the same key waits instead of reading again.
  std::unordered_map<BrickKey, std::shared_future<BrickSamples>, KeyHash> loading_;
  BrickCacheStats stats_;

  enum class Origin { get, prefetch };
  BrickSamples load(const BrickKey& key, std::unique_lock<std::mutex>& lock, Origin origin);
  void insert(const BrickKey& key, const BrickSamples& samples, std::int64_t bytes);
  void check_key(const BrickKey& key) const;
};

}  // namespace tsp

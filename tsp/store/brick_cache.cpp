#include "tsp/store/brick_cache.h"

#include <cassert>
#include <exception>
#include <string>

#include "tsp/core/error.h"

namespace tsp {

std::size_t BrickCache::KeyHash::operator()(const BrickKey& k) const {
  std::uint64_t v = (std::uint64_t(std::uint32_t(k.brick)) << 32) | std::uint32_t(k.step);
  v ^= v >> 33;
  v *= 0xff51afd7ed558ccdULL;
  v ^= v >> 33;
  return std::size_t(v);
}

BrickCache::BrickCache(const BrickStore& store, std::int64_t budget_bytes)
    : store_(store), budget_(budget_bytes) {
  if (budget_bytes < 0)
    throw UsageError("brick cache budget must be >= 0 bytes, got " + std::to_string(budget_bytes));
}

std::int64_t BrickCache::entry_bytes(int brick) const {
  const int channels = store_.tree().has_stencil() ? 2 : 1;
  return store_.tree().octree().lattice(brick).count() * channels *
         std::int64_t(sizeof(std::uint16_t));
}

void BrickCache::check_key(const BrickKey& key) const {
  assert(key.brick >= 0 && key.brick < store_.tree().octree().stored_brick_count());
  assert(key.step >= 0 && key.step < store_.tree().time().steps());
  (void)key;
}

BrickSamples BrickCache::get(int brick, int step) {
  const BrickKey key{brick, step};
  check_key(key);
  std::unique_lock lock(mu_);
  if (auto it = index_.find(key); it != index_.end()) {
    lru_.splice(lru_.begin(), lru_, it->second);
    ++stats_.hits;
    return it->second->samples;
  }
  if (auto it = loading_.find(key); it != loading_.end()) {
    const std::shared_future<BrickSamples> pending = it->second;
    ++stats_.waited;
    lock.unlock();
    BrickSamples s = pending.get();  // rethrows the reader's exception
    lock.lock();
    ++stats_.hits;
    return s;
  }
  ++stats_.misses;
  return load(key, lock, Origin::get);
}

bool BrickCache::contains(int brick, int step) const {
  std::lock_guard lock(mu_);
  return index_.count(BrickKey{brick, step}) != 0;
}

int BrickCache::prefetch(std::span<const BrickKey> keys) {
  std::int64_t loaded_bytes = 0;
  int loaded = 0;
  for (const BrickKey& key : keys) {
    check_key(key);
    const std::int64_t bytes = entry_bytes(key.brick);
    std::unique_lock lock(mu_);
    if (index_.count(key) || loading_.count(key)) continue;
    if (loaded_bytes + bytes > budget_) break;
    load(key, lock, Origin::prefetch);
    loaded_bytes += bytes;
    ++loaded;
  }
  return loaded;
}

void BrickCache::clear() {
  std::lock_guard lock(mu_);
  lru_.clear();
  index_.clear();
  stats_.resident_count = stats_.resident_bytes = 0;
}

BrickCacheStats BrickCache::stats() const {
  std::lock_guard lock(mu_);
  return stats_;
}

BrickSamples BrickCache::load(const BrickKey& key, std::unique_lock<std::mutex>& lock,
                              Origin origin) {
  std::promise<BrickSamples> promise;
  loading_.emplace(key, promise.get_future().share());
  const std::int64_t bytes = entry_bytes(key.brick);
  lock.unlock();
  BrickSamples samples;
  try {
    auto buf = std::make_shared<std::vector<std::uint16_t>>(
        std::size_t(bytes / std::int64_t(sizeof(std::uint16_t))));
    const std::size_t n = std::size_t(store_.tree().octree().lattice(key.brick).count());
    store_.read_brick(key.brick, key.step, std::span<std::uint16_t>(buf->data(), n));
    if (store_.tree().has_stencil()) {
      std::vector<std::uint8_t> inside(n);
      store_.read_inside(key.brick, key.step, inside);
      std::copy(inside.begin(), inside.end(), buf->begin() + std::ptrdiff_t(n));
    }
    samples = std::move(buf);
  } catch (...) {
    lock.lock();
    loading_.erase(key);
    promise.set_exception(std::current_exception());
    throw;
  }
  lock.lock();
  loading_.erase(key);
  stats_.bytes_read += bytes;
  if (origin == Origin::prefetch) ++stats_.prefetched;
  insert(key, samples, bytes);
  promise.set_value(samples);
  return samples;
}

void BrickCache::insert(const BrickKey& key, const BrickSamples& samples, std::int64_t bytes) {
  if (bytes > budget_) return;  // would evict everything and still not fit: hand it out only
  lru_.push_front(Entry{key, samples, bytes});
  index_.emplace(key, lru_.begin());
  ++stats_.resident_count;
  stats_.resident_bytes += bytes;
  while (stats_.resident_bytes > budget_) {
    const Entry& victim = lru_.back();
    stats_.resident_bytes -= victim.bytes;
    --stats_.resident_count;
    ++stats_.evictions;
    index_.erase(victim.key);
    lru_.pop_back();
  }
}

}  // namespace tsp

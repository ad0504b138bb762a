#include "tsp/frame/texture_cache.h"

#include <algorithm>
#include <cassert>
#include <iterator>
#include <string>

#include "tsp/core/error.h"

namespace tsp {

namespace {
void check_budget(std::int64_t budget) {
  if (budget < 0)
    throw UsageError("texture cache budget must be >= 0 bytes, got " + std::to_string(budget));
}
}  // namespace

std::size_t TextureKeyHash::operator()(const TextureKey& k) const {
  // Bricks < 2^32, steps < 2^24, levels < 2^8 in any tree we can hold: pack, then mix.
  std::uint64_t v = (std::uint64_t(std::uint32_t(k.brick)) << 32) ^
                    (std::uint64_t(std::uint32_t(k.t0)) << 8) ^
                    std::uint64_t(std::uint8_t(k.level)) ^
                    (std::uint64_t(std::uint32_t(k.t1 + 1)) << 20);
  v ^= v >> 33;
  v *= 0xff51afd7ed558ccdULL;
  v ^= v >> 33;
  return std::size_t(v);
}

TextureCache::TextureCache(std::int64_t budget_bytes, CachePolicy policy)
    : budget_(budget_bytes), policy_(policy) {
  check_budget(budget_bytes);
}

void TextureCache::begin_frame() {
  assert(!in_frame_ && "begin_frame() twice without end_frame()");
  in_frame_ = true;
  ++frame_;
  stats_.frame_hits = stats_.frame_misses = stats_.frame_uploaded_bytes = 0;
}

TextureRequest TextureCache::request(const TextureKey& key, std::int64_t bytes) {
  assert(in_frame_ && "request() outside a frame");
  assert(bytes > 0);
  TextureRequest r;
  if (auto found = index_.find(key); found != index_.end()) {
    const List::iterator it = found->second;
    assert(it->bytes == bytes && "a texture key must always have the same size");
    it->frame = frame_;
    lru_.splice(lru_.begin(), lru_, it);
    r.hit = true;
    ++stats_.hits;
    ++stats_.frame_hits;
    return r;
  }
  // Make room among textures this frame has not drawn (yet); pinned ones stay even when the
  // frame alone needs more than the budget.
  trim(budget_ - bytes, r.evicted);
  lru_.push_front(Entry{key, bytes, frame_});
  index_.emplace(key, lru_.begin());
  stats_.resident_count++;
  stats_.resident_bytes += bytes;
  stats_.peak_bytes = std::max(stats_.peak_bytes, stats_.resident_bytes);
  ++stats_.misses;
  ++stats_.frame_misses;
  stats_.frame_uploaded_bytes += bytes;
  return r;
}

std::vector<TextureKey> TextureCache::end_frame() {
  assert(in_frame_ && "end_frame() without begin_frame()");
  std::vector<TextureKey> out;
  if (policy_ == CachePolicy::off) {
    for (auto it = lru_.begin(); it != lru_.end();) {
      const auto next = std::next(it);
      if (it->frame != frame_) erase(it, out);
      it = next;
    }
  }
  in_frame_ = false;  // unpins this frame's textures, so the trim below may take them too
  trim(budget_, out);
  return out;
}

std::vector<TextureKey> TextureCache::drop_unreachable(
    const std::function<bool(const TextureKey&)>& reachable) {
  assert(!in_frame_ && "drop_unreachable() inside a frame");
  std::vector<TextureKey> out;
  for (auto it = lru_.begin(); it != lru_.end();) {
    const auto next = std::next(it);
    if (!reachable(it->key)) erase(it, out);
    it = next;
  }
  return out;
}

std::vector<TextureKey> TextureCache::drop_unreachable(const TextureKeySet& reachable) {
  return drop_unreachable([&](const TextureKey& k) { return reachable.count(k) != 0; });
}

std::vector<TextureKey> TextureCache::clear() {
  return drop_unreachable([](const TextureKey&) { return false; });
}

void TextureCache::set_policy(CachePolicy policy) {
  assert(!in_frame_ && "set_policy() inside a frame");
  policy_ = policy;
}

std::vector<TextureKey> TextureCache::set_budget(std::int64_t budget_bytes) {
  assert(!in_frame_ && "set_budget() inside a frame");
  check_budget(budget_bytes);
  budget_ = budget_bytes;
  std::vector<TextureKey> out;
  trim(budget_, out);
  return out;
}

std::vector<TextureKey> TextureCache::lru_order() const {
  std::vector<TextureKey> out;
  out.reserve(lru_.size());
  for (const Entry& e : lru_) out.push_back(e.key);
  return out;
}

void TextureCache::erase(List::iterator it, std::vector<TextureKey>& out) {
  out.push_back(it->key);
  stats_.resident_count--;
  stats_.resident_bytes -= it->bytes;
  ++stats_.evictions;
  index_.erase(it->key);
  lru_.erase(it);
}

void TextureCache::trim(std::int64_t limit, std::vector<TextureKey>& out) {
  // Pinned entries were all moved to the front this frame, so the unpinned ones form the tail.
  while (stats_.resident_bytes > limit && !lru_.empty() && !pinned(lru_.back()))
    erase(std::prev(lru_.end()), out);
}

}  // namespace tsp

// Texture cache policy (spec §8, paper §4.3): which brick textures stay resident on the GPU.
// Pure bookkeeping, no GL: the renderer maps every decision (upload, keep, delete) onto its own
// texture objects. Rules and their reasons: docs/caching.md.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace tsp {

/// A brick texture: brick index, the step whose data it holds, LOD level (0 = full
/// resolution) and, for a span's temporal mean (SpanStep::mean), the span's last step t1 > t0
/// (then t0 is its first). Textures hold scalars, so no transfer function is part of the key.
struct TextureKey {
  int brick = -1;
  int t0 = 0;
  int level = 0;
  int t1 = -1;  ///< > t0: the mean of steps t0..t1; otherwise step t0 alone
  /// True when the texture holds a span's mean rather than one step.
  bool is_mean() const { return t1 > t0; }
  /// The last step whose data it holds: t1 for a mean, else t0.
  int last_step() const { return is_mean() ? t1 : t0; }
  bool operator==(const TextureKey&) const = default;
};

/// Hash of a TextureKey, for unordered containers.
struct TextureKeyHash {
  /// Mixes the three fields.
  std::size_t operator()(const TextureKey& k) const;
};

/// A set of texture keys.
using TextureKeySet = std::unordered_set<TextureKey, TextureKeyHash>;

/// Cache on: textures persist across frames within the budget. Cache off: a texture persists
/// only into the next frame, and only if that frame draws it too (spec §8).
enum class CachePolicy { on, off };

/// What request() decided.
struct TextureRequest {
  bool hit = false;                 ///< resident already: reuse it (RT); else upload it (NT)
  std::vector<TextureKey> evicted;  ///< delete these now, before uploading the new texture
};

/// Counters; the frame_* ones are reset by begin_frame().
struct TextureCacheStats {
  std::int64_t resident_count = 0;        ///< textures held now
  std::int64_t resident_bytes = 0;        ///< their bytes
  std::int64_t peak_bytes = 0;            ///< largest resident_bytes ever reached
  std::int64_t hits = 0;                  ///< requests found resident, since construction
  std::int64_t misses = 0;                ///< requests that needed an upload
  std::int64_t evictions = 0;             ///< textures deleted by any rule
  std::int64_t frame_hits = 0;            ///< hits in the current (or last) frame
  std::int64_t frame_misses = 0;          ///< uploads in the current (or last) frame
  std::int64_t frame_uploaded_bytes = 0;  ///< bytes uploaded in the current (or last) frame
};

/// LRU texture cache with a byte budget. Usage per frame: begin_frame(); request() every
/// texture the frame draws; end_frame(). A texture requested in the current frame is pinned:
/// nothing evicts it before end_frame(). When the frame's own textures exceed the budget the
/// cache goes over budget for that frame and end_frame() trims it back (see docs/caching.md).
class TextureCache {
 public:
  /// A cache of budget_bytes (≥ 0) under policy. Throws UsageError on a negative budget.
  TextureCache(std::int64_t budget_bytes, CachePolicy policy);

  /// Starts a frame: clears the frame counters and unpins every texture. Asserts no frame is open.
  void begin_frame();
  /// The current frame draws texture key of `bytes` bytes (> 0). A resident key is a hit and
  /// becomes most recently used; otherwise it is inserted after evicting unpinned textures,
  /// least recently used first, until it fits the budget (or none is left to evict). A key
  /// requested twice in one frame is a hit the second time. Asserts a frame is open and that a
  /// resident key is requested with the bytes it was inserted with.
  TextureRequest request(const TextureKey& key, std::int64_t bytes);
  /// Ends the frame and returns the textures to delete after drawing it: with policy off every
  /// texture the frame did not request; then, with either policy, least recently used textures
  /// until the budget holds. Asserts a frame is open.
  std::vector<TextureKey> end_frame();

  /// Deletes every resident texture for which reachable(key) is false (after a tolerance change)
  /// and returns them. Asserts no frame is open.
  std::vector<TextureKey> drop_unreachable(const std::function<bool(const TextureKey&)>& reachable);
  /// Same, keeping exactly the keys in reachable.
  std::vector<TextureKey> drop_unreachable(const TextureKeySet& reachable);
  /// Deletes every texture and returns them. Asserts no frame is open.
  std::vector<TextureKey> clear();

  /// Changes the policy; takes effect at the next end_frame(). Asserts no frame is open.
  void set_policy(CachePolicy policy);
  /// Changes the budget (≥ 0) and returns the textures evicted (LRU) to meet it. Throws
  /// UsageError on a negative budget; asserts no frame is open.
  std::vector<TextureKey> set_budget(std::int64_t budget_bytes);

  /// True when key is resident.
  bool contains(const TextureKey& key) const { return index_.count(key) != 0; }
  /// Resident keys, most recently used first.
  std::vector<TextureKey> lru_order() const;
  /// Counters.
  const TextureCacheStats& stats() const { return stats_; }
  /// Byte budget.
  std::int64_t budget() const { return budget_; }
  /// Policy.
  CachePolicy policy() const { return policy_; }
  /// True between begin_frame() and end_frame().
  bool in_frame() const { return in_frame_; }

 private:
  struct Entry {
    TextureKey key;
    std::int64_t bytes = 0;
    std::uint64_t frame = 0;  // last frame that requested it
  };
  using List = std::list<Entry>;  // front = most recently used
  std::int64_t budget_;
  CachePolicy policy_;
  bool in_frame_ = false;
  std::uint64_t frame_ = 0;  // number of the open (or last) frame; entries of frame_ are pinned
  List lru_;
  std::unordered_map<TextureKey, List::iterator, TextureKeyHash> index_;
  TextureCacheStats stats_;
  bool pinned(const Entry& e) const { return in_frame_ && e.frame == frame_; }
  void erase(List::iterator it, std::vector<TextureKey>& out);
  void trim(std::int64_t limit, std::vector<TextureKey>& out);  // unpinned LRU until ≤ limit
};

}  // namespace tsp

// Background brick reads for playback: the player hands over the bricks the next steps' frames
// will upload, and a BackgroundWorker reads them into a BrickCache, so a frame finds its bricks
// in RAM instead of waiting for the disk (docs/player.md).
#pragma once
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "tsp/core/background_worker.h"
#include "tsp/store/brick_cache.h"

namespace tsp {

/// Bricks read per BrickCache::prefetch call, so that a newer request replaces the rest of an
/// older one quickly (a scrub away from the played steps).
inline constexpr int kPrefetchChunk = 4;

/// Reads requested bricks into a BrickCache on one background thread, kPrefetchChunk bricks per
/// job. Thread-safe: any thread may call the members.
class BrickPrefetcher {
 public:
  /// An idle prefetcher; cache must outlive it. Never throws.
  explicit BrickPrefetcher(BrickCache& cache);
  /// Drops the pending request, waits for the chunk being read and joins the thread.
  ~BrickPrefetcher() = default;
  BrickPrefetcher(const BrickPrefetcher&) = delete;
  BrickPrefetcher& operator=(const BrickPrefetcher&) = delete;

  /// Replaces the pending request with keys (read in order; keys already cached cost nothing);
  /// the chunk being read goes on. Throws std::system_error when the thread cannot start.
  void request(std::vector<BrickKey> keys);
  /// Blocks until every requested key has been handled (for tests and benchmarks). Read errors
  /// are not thrown (last_error()); anything else a read threw (std::bad_alloc) is rethrown.
  void wait_idle();
  /// Bricks read so far. Never throws.
  std::int64_t bricks_read() const;
  /// The last read error (the frame that needs the brick reports it too), empty if none.
  std::string last_error() const;

 private:
  void read_chunk(const std::vector<BrickKey>& chunk);
  BrickCache& cache_;
  mutable std::mutex mutex_;  // guards read_ and error_
  std::int64_t read_ = 0;
  std::string error_;
  BackgroundWorker worker_;  // last: its thread ends before the members above go
};

}  // namespace tsp

// Background brick reads for playback: the player hands over the bricks the next steps' frames
// will upload, and one worker thread reads them into a BrickCache, so a frame finds its bricks
// in RAM instead of waiting for the disk (docs/player.md).
#pragma once
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "tsp/store/brick_cache.h"

namespace tsp {

/// Bricks read per BrickCache::prefetch call, so that a newer request replaces the rest of an
/// older one quickly (a scrub away from the played steps).
inline constexpr int kPrefetchChunk = 4;

/// One worker thread reading requested bricks into a BrickCache.
class BrickPrefetcher {
 public:
  /// Starts the worker; cache must outlive the BrickPrefetcher.
  explicit BrickPrefetcher(BrickCache& cache);
  /// Stops the worker after its current chunk and joins it.
  ~BrickPrefetcher();
  BrickPrefetcher(const BrickPrefetcher&) = delete;
  BrickPrefetcher& operator=(const BrickPrefetcher&) = delete;

  /// Replaces the pending request with keys (read in order; keys already cached cost nothing).
  void request(std::vector<BrickKey> keys);
  /// Blocks until every requested key has been handled (for tests and benchmarks).
  void wait_idle();
  /// Bricks read so far.
  std::int64_t bricks_read() const;
  /// The last read error (the frame that needs the brick reports it too), empty if none.
  std::string last_error() const;

 private:
  void run();
  BrickCache& cache_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<BrickKey> pending_;
  std::size_t next_ = 0;
  bool busy_ = false;  // a chunk is being read
  std::int64_t read_ = 0;
  std::string error_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace tsp

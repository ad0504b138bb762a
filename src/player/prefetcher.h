// Background brick reads for playback: the player hands over the bricks the next steps' frames
// will upload, and one worker thread reads them into the renderer's BrickCache, so a frame
// finds its bricks in RAM instead of waiting for the disk (docs/player.md).
#pragma once
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "tsp/brick_cache.h"

namespace tspplayer {

/// Bricks read per BrickCache::prefetch call, so that a newer request replaces the rest of an
/// older one quickly (a scrub away from the played steps).
inline constexpr int kPrefetchChunk = 4;

/// One worker thread reading requested bricks into a BrickCache.
class Prefetcher {
 public:
  /// Starts the worker; cache must outlive the Prefetcher.
  explicit Prefetcher(tsp::BrickCache& cache);
  /// Stops the worker after its current chunk and joins it.
  ~Prefetcher();
  Prefetcher(const Prefetcher&) = delete;
  Prefetcher& operator=(const Prefetcher&) = delete;

  /// Replaces the pending request with keys (read in order; keys already cached cost nothing).
  void request(std::vector<tsp::BrickKey> keys);
  /// Bricks read so far.
  std::int64_t bricks_read() const;
  /// The last read error (the frame that needs the brick reports it too), empty if none.
  std::string last_error() const;

 private:
  void run();
  tsp::BrickCache& cache_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<tsp::BrickKey> pending_;
  std::size_t next_ = 0;
  std::int64_t read_ = 0;
  std::string error_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace tspplayer

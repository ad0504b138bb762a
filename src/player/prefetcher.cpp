#include "player/prefetcher.h"

#include <algorithm>
#include <span>

#include "tsp/error.h"

namespace tspplayer {

Prefetcher::Prefetcher(tsp::BrickCache& cache) : cache_(cache), thread_([this] { run(); }) {}

Prefetcher::~Prefetcher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void Prefetcher::request(std::vector<tsp::BrickKey> keys) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_ = std::move(keys);
    next_ = 0;
  }
  cv_.notify_all();
}

std::int64_t Prefetcher::bricks_read() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return read_;
}

std::string Prefetcher::last_error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

void Prefetcher::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    cv_.wait(lock, [this] { return stop_ || next_ < pending_.size(); });
    if (stop_) return;
    const std::size_t end = std::min(pending_.size(), next_ + std::size_t(kPrefetchChunk));
    std::vector<tsp::BrickKey> chunk(pending_.begin() + std::ptrdiff_t(next_),
                                     pending_.begin() + std::ptrdiff_t(end));
    next_ = end;
    lock.unlock();
    int n = 0;
    std::string error;
    try {
      n = cache_.prefetch(chunk);
    } catch (const tsp::Error& e) {
      error = e.what();  // the frame that needs the brick reads it again and reports it
    }
    lock.lock();
    read_ += n;
    if (!error.empty()) error_ = error;
  }
}

}  // namespace tspplayer

#include "tsp/store/brick_prefetcher.h"

#include <algorithm>
#include <span>

#include "tsp/core/error.h"

namespace tsp {

BrickPrefetcher::BrickPrefetcher(BrickCache& cache) : cache_(cache), thread_([this] { run(); }) {}

BrickPrefetcher::~BrickPrefetcher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void BrickPrefetcher::request(std::vector<BrickKey> keys) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_ = std::move(keys);
    next_ = 0;
  }
  cv_.notify_all();
}

void BrickPrefetcher::wait_idle() {
  std::unique_lock<std::mutex> lock(mutex_);
  cv_.wait(lock, [this] { return !busy_ && next_ >= pending_.size(); });
}

std::int64_t BrickPrefetcher::bricks_read() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return read_;
}

std::string BrickPrefetcher::last_error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

void BrickPrefetcher::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    cv_.wait(lock, [this] { return stop_ || next_ < pending_.size(); });
    if (stop_) return;
    const std::size_t end = std::min(pending_.size(), next_ + std::size_t(kPrefetchChunk));
    std::vector<BrickKey> chunk(pending_.begin() + std::ptrdiff_t(next_),
                                pending_.begin() + std::ptrdiff_t(end));
    next_ = end;
    busy_ = true;
    lock.unlock();
    int n = 0;
    std::string error;
    try {
      n = cache_.prefetch(chunk);
    } catch (const Error& e) {
      error = e.what();  // the frame that needs the brick reads it again and reports it
    }
    lock.lock();
    read_ += n;
    if (!error.empty()) error_ = error;
    busy_ = false;
    cv_.notify_all();  // wait_idle
  }
}

}  // namespace tsp

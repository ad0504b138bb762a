#include "tsp/store/brick_prefetcher.h"

#include <algorithm>
#include <span>

#include "tsp/core/error.h"

namespace tsp {

BrickPrefetcher::BrickPrefetcher(BrickCache& cache) : cache_(cache) {}

void BrickPrefetcher::request(std::vector<BrickKey> keys) {
  worker_.cancel_pending();
  for (std::size_t first = 0; first < keys.size(); first += std::size_t(kPrefetchChunk)) {
    const std::size_t end = std::min(keys.size(), first + std::size_t(kPrefetchChunk));
    worker_.submit([this, chunk = std::vector<BrickKey>(keys.begin() + std::ptrdiff_t(first),
                                                        keys.begin() + std::ptrdiff_t(end))](
                       std::stop_token) { read_chunk(chunk); });
  }
}

void BrickPrefetcher::wait_idle() { worker_.wait(); }

std::int64_t BrickPrefetcher::bricks_read() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return read_;
}

std::string BrickPrefetcher::last_error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

void BrickPrefetcher::read_chunk(const std::vector<BrickKey>& chunk) {
  int n = 0;
  std::string error;
  try {
    n = cache_.prefetch(chunk);
  } catch (const Error& e) {
    error = e.what();  // the frame that needs the brick reads it again and reports it
  }
  std::lock_guard<std::mutex> lock(mutex_);
  read_ += n;
  if (!error.empty()) error_ = error;
}

}  // namespace tsp

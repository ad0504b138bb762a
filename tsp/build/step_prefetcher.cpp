#include "tsp/build/step_prefetcher.h"

#include <cassert>

namespace tsp {

StepPrefetcher::StepPrefetcher(VolumeSource& source, StepHook on_read, int first, int stride)
    : source_(source), on_read_(std::move(on_read)), first_(first), stride_(stride) {
  assert(first >= 0 && stride >= 1);
  thread_ = std::thread([this] { run(); });
}

StepPrefetcher::~StepPrefetcher() {
  {
    std::lock_guard lock(mutex_);
    cancel_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void StepPrefetcher::run() {
  const std::size_t voxels = std::size_t(source_.dims().count());
  for (int t = first_; t < source_.steps(); t += stride_) {
    int b;
    {
      std::unique_lock lock(mutex_);
      cv_.wait(lock, [&] { return cancel_ || !free_.empty(); });
      if (cancel_) return;
      b = free_.front();
      free_.pop_front();
    }
    try {
      buffers_[b].resize(voxels);
      if (source_.has_stencil()) {
        masks_[b].resize(voxels);
        source_.read_step_inside(t, buffers_[b], masks_[b]);
      } else {
        source_.read_step(t, buffers_[b]);
      }
      if (on_read_) on_read_(t, buffers_[b], masks_[b]);
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
      cv_.notify_all();
      return;
    }
    {
      std::lock_guard lock(mutex_);
      ready_.push_back(b);
    }
    cv_.notify_all();
  }
}

const std::vector<float>& StepPrefetcher::next() {
  std::unique_lock lock(mutex_);
  assert(current_ < 0);
  cv_.wait(lock, [&] { return !ready_.empty() || error_; });
  if (ready_.empty()) std::rethrow_exception(error_);
  current_ = ready_.front();
  ready_.pop_front();
  return buffers_[current_];
}

void StepPrefetcher::release() {
  {
    std::lock_guard lock(mutex_);
    assert(current_ >= 0);
    free_.push_back(current_);
    current_ = -1;
  }
  cv_.notify_all();
}

}  // namespace tsp

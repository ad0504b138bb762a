#include "tsp/build/slab_prefetcher.h"

#include <algorithm>
#include <atomic>
#include <cassert>

namespace tsp {

SlabPrefetcher::SlabPrefetcher(VolumeSource& source, int slab_planes, SlabHook on_read, int first,
                               int stride)
    : source_(source),
      slab_planes_(slab_planes),
      on_read_(std::move(on_read)),
      first_(first),
      stride_(stride),
      whole_(source.has_stencil() || !source.reads_slabs()),
      worker_([this] {
        std::lock_guard lock(mutex_);  // next() tests failed() under it: no lost wake-up
        cv_.notify_all();
      }) {
  assert(slab_planes >= 1 && first >= 0 && stride >= 1);
  worker_.submit([this](std::stop_token stop) { run(std::move(stop)); });
}

// A buffer no slab holds any more (only this list does), or a new one.
std::shared_ptr<SlabBuffer> SlabPrefetcher::free_buffer() {
  for (const std::shared_ptr<SlabBuffer>& b : buffers_)
    if (b.use_count() == 1) {
      // Pairs with the release of the consumer's last reference: its reads of the planes
      // happen before this thread writes the buffer again.
      std::atomic_thread_fence(std::memory_order_acquire);
      return b;
    }
  buffers_.push_back(std::make_shared<SlabBuffer>());
  return buffers_.back();
}

void SlabPrefetcher::run(std::stop_token stop) {
  const Dims d = source_.dims();
  const std::int64_t plane = std::int64_t(d.x) * d.y;
  const int unit = whole_ ? d.z : slab_planes_;
  for (int t = first_; t < source_.steps(); t += stride_)
    for (int z0 = 0; z0 < d.z; z0 += unit) {
      {
        std::unique_lock lock(mutex_);
        if (!cv_.wait(lock, stop, [&] { return ready_.empty(); })) return;  // stopped
      }
      const int z1 = std::min(d.z, z0 + unit);
      std::vector<Slab> slabs;
      // An exception here ends the job; the worker keeps it for next().
      std::shared_ptr<SlabBuffer> b = free_buffer();
      b->z0 = z0;
      b->values.resize(std::size_t((z1 - z0) * plane));
      if (source_.has_stencil()) {
        inside_.resize(b->values.size());
        source_.read_step_inside(t, b->values, inside_);
        b->mask.resize(inside_.size());
        std::transform(inside_.begin(), inside_.end(), b->mask.begin(),
                       [](std::uint8_t i) { return i ? 1.f : 0.f; });
      } else if (whole_) {
        source_.read_step(t, b->values);
      } else {
        source_.read_slab(t, z0, z1, b->values);
      }
      if (on_read_) on_read_(Slab{t, z0, z1, b, plane});
      for (int s = z0; s < z1; s += slab_planes_)
        slabs.push_back(Slab{t, s, std::min(z1, s + slab_planes_), b, plane});
      {
        std::lock_guard lock(mutex_);
        ready_.insert(ready_.end(), slabs.begin(), slabs.end());
      }
      cv_.notify_all();
    }
}

Slab SlabPrefetcher::next() {
  std::unique_lock lock(mutex_);
  cv_.wait(lock, [&] { return !ready_.empty() || worker_.failed(); });
  if (ready_.empty()) worker_.rethrow_if_failed();
  Slab s = std::move(ready_.front());
  ready_.pop_front();
  if (ready_.empty()) cv_.notify_all();
  return s;
}

}  // namespace tsp

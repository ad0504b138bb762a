// Reads a VolumeSource's steps in z-slabs, in order, on a background thread, one unit ahead of
// the consumer: a slab when the source reads parts of a step (VolumeSource::reads_slabs), else
// a whole step, handed out as slabs that share it. The consumer keeps the slabs it still needs
// and drops the others; what it drops is reused for later reads.
#pragma once
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <stop_token>
#include <vector>

#include "tsp/core/background_worker.h"
#include "tsp/source/volume_source.h"

namespace tsp {

/// Samples read by SlabPrefetcher: one slab, or a whole step that several slabs share.
struct SlabBuffer {
  int z0 = 0;                 ///< first plane held
  std::vector<float> values;  ///< planes z0 … of the step, x fastest
  std::vector<float> mask;    ///< the stencil as 1/0 floats laid out like values; empty without
};

/// Planes z0 … z1 − 1 of one step.
struct Slab {
  int step = -1, z0 = 0, z1 = 0;
  std::shared_ptr<const SlabBuffer> data;  ///< keeps the planes alive while the slab is held
  std::int64_t plane_size = 0;             ///< floats per plane (d.x · d.y)
  /// Plane z (z0 ≤ z < z1) of the values. Never throws.
  const float* plane(int z) const { return data->values.data() + (z - data->z0) * plane_size; }
  /// Plane z of the stencil mask; null without a stencil. Never throws.
  const float* mask_plane(int z) const {
    return data->mask.empty() ? nullptr : data->mask.data() + (z - data->z0) * plane_size;
  }
};

/// Double-buffered slab reader: slabs of slab_planes planes (the last of a step may be thinner)
/// of steps first, first + stride, …, in step then z order, read by one job on a BackgroundWorker.
/// read_step / read_slab are called only from the worker's thread. Not thread-safe: one consumer
/// thread calls next().
class SlabPrefetcher {
 public:
  /// Called on the prefetch thread with each unit read (a slab, or a whole step as one slab), in
  /// order.
  using SlabHook = std::function<void(const Slab&)>;
  /// Starts reading on the worker's thread, running on_read (may be empty) on each unit; errors
  /// of either are rethrown by next(). Never throws but std::system_error.
  SlabPrefetcher(VolumeSource& source, int slab_planes, SlabHook on_read = {}, int first = 0,
                 int stride = 1);
  /// Stops the reads (after the one in progress) and joins the worker's thread.
  ~SlabPrefetcher() = default;
  SlabPrefetcher(const SlabPrefetcher&) = delete;
  SlabPrefetcher& operator=(const SlabPrefetcher&) = delete;
  /// Waits for the next slab in order; rethrows the source's or the hook's exception.
  Slab next();
  /// True when the source is read a whole step at a time (it cannot read slabs). Never throws.
  bool whole_steps() const { return whole_; }

 private:
  void run(std::stop_token stop);
  std::shared_ptr<SlabBuffer> free_buffer();
  VolumeSource& source_;
  int slab_planes_;
  SlabHook on_read_;
  int first_, stride_;
  bool whole_;
  std::vector<std::shared_ptr<SlabBuffer>> buffers_;  // every buffer made; free when only here
  std::vector<std::uint8_t> inside_;  // a stencil step as read, before it becomes a mask
  std::mutex mutex_;
  std::condition_variable_any cv_;  // a slab is ready or taken, the reads failed, or stop
  std::deque<Slab> ready_;
  BackgroundWorker worker_;  // last: its thread ends before the members above go
};

}  // namespace tsp

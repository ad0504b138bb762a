// Reads a VolumeSource's steps in order on a background thread, one step ahead of the consumer.
#pragma once
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "tsp/source/volume_source.h"

namespace tsp {

/// Double-buffered step reader: while the caller works on step t, step t+1 is being read, so at
/// most two steps are in memory. read_step is only ever called from the prefetch thread.
class StepPrefetcher {
 public:
  /// Called on the prefetch thread with each step right after it was read (in step order);
  /// inside is the step's stencil, empty when the source has none.
  using StepHook = std::function<void(int step, const std::vector<float>& samples,
                                      const std::vector<std::uint8_t>& inside)>;
  /// Starts reading steps first, first + stride, … of source on a new thread, running on_read
  /// (may be empty) on each; errors of either are rethrown by next().
  explicit StepPrefetcher(VolumeSource& source, StepHook on_read = {}, int first = 0,
                          int stride = 1);
  /// Stops the thread (after the read in progress) and joins it.
  ~StepPrefetcher();
  StepPrefetcher(const StepPrefetcher&) = delete;
  StepPrefetcher& operator=(const StepPrefetcher&) = delete;
  /// Waits for the next step in order and returns its samples; rethrows the source's exception.
  /// The buffer stays valid until release().
  const std::vector<float>& next();
  /// The stencil of the step the last next() returned (empty when the source has none); valid
  /// until release().
  const std::vector<std::uint8_t>& inside() const { return masks_[current_]; }
  /// Gives the buffer returned by the last next() back for reading further steps.
  void release();

 private:
  void run();
  VolumeSource& source_;
  StepHook on_read_;
  int first_, stride_;
  std::vector<float> buffers_[2];
  std::vector<std::uint8_t> masks_[2];
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<int> free_{0, 1};
  std::deque<int> ready_;
  int current_ = -1;
  bool cancel_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace tsp

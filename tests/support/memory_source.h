// An in-memory VolumeSource for tests: per-step float vectors, optionally failing at a step.
#pragma once
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "tsp/source/volume_source.h"

namespace tsptest {

/// A time series held in memory; read_step copies step t. With fail_at ≥ 0, reading that step
/// throws tsp::IoError (to test clean-up after a failing source).
class MemorySource : public tsp::VolumeSource {
 public:
  /// steps[t] holds dims.count() floats, x fastest.
  MemorySource(tsp::Dims dims, std::vector<std::vector<float>> steps, int fail_at = -1);
  /// A series whose value at (x, y, z, t) is f(x, y, z, t).
  static MemorySource from_function(tsp::Dims dims, int steps,
                                    const std::function<float(int, int, int, int)>& f);
  tsp::Dims dims() const override { return dims_; }
  int steps() const override { return int(steps_.size()); }
  std::string describe() const override { return "memory source " + tsp::to_string(dims_); }
  void read_step(int t, std::span<float> out) override;
  bool reads_slabs() const override { return reads_slabs_; }
  /// Copies planes z0 … z1 − 1 of step t (fails like read_step).
  void read_slab(int t, int z0, int z1, std::span<float> out) override;
  /// Whether a builder may read slabs (read_slab) instead of whole steps; false at first.
  void set_reads_slabs(bool on) { reads_slabs_ = on; }
  /// Number of read_slab calls so far (made on any thread). Thread-safe.
  int slab_reads() const;
  /// Blocks until read_slab has been called at least n times (on any thread). Thread-safe.
  void wait_for_slab_reads(int n) const;
  /// Sample (x, y, z) of step t.
  float at(int x, int y, int z, int t) const {
    return steps_[t][x + std::size_t(dims_.x) * (y + std::size_t(dims_.y) * z)];
  }
  /// Makes reading step t throw tsp::IoError (−1: never).
  void set_fail_at(int t) { fail_at_ = t; }
  /// Number of read_step calls so far.
  int reads() const { return reads_; }

 private:
  tsp::Dims dims_;
  std::vector<std::vector<float>> steps_;
  int fail_at_;
  int reads_ = 0;
  bool reads_slabs_ = false;
  // read_slab's count, shared with waiting threads (the source itself stays movable).
  struct Count {
    std::mutex m;
    std::condition_variable changed;
    int n = 0;
  };
  std::shared_ptr<Count> slab_reads_ = std::make_shared<Count>();
};

}  // namespace tsptest

#include "support/memory_source.h"

#include <algorithm>
#include <cassert>

#include "tsp/core/error.h"

namespace tsptest {

MemorySource::MemorySource(tsp::Dims dims, std::vector<std::vector<float>> steps, int fail_at)
    : dims_(dims), steps_(std::move(steps)), fail_at_(fail_at) {
  for (const auto& s : steps_) assert(std::int64_t(s.size()) == dims_.count());
}

MemorySource MemorySource::from_function(tsp::Dims dims, int steps,
                                         const std::function<float(int, int, int, int)>& f) {
  std::vector<std::vector<float>> data(steps, std::vector<float>(std::size_t(dims.count())));
  for (int t = 0; t < steps; ++t)
    for (int z = 0; z < dims.z; ++z)
      for (int y = 0; y < dims.y; ++y)
        for (int x = 0; x < dims.x; ++x)
          data[t][x + std::size_t(dims.x) * (y + std::size_t(dims.y) * z)] = f(x, y, z, t);
  return MemorySource(dims, std::move(data));
}

void MemorySource::read_step(int t, std::span<float> out) {
  assert(t >= 0 && t < steps() && std::int64_t(out.size()) == dims_.count());
  ++reads_;
  if (t == fail_at_)
    throw tsp::IoError(describe() + ": step " + std::to_string(t) + ": simulated read failure");
  std::copy(steps_[t].begin(), steps_[t].end(), out.begin());
}

void MemorySource::read_slab(int t, int z0, int z1, std::span<float> out) {
  const std::int64_t plane = std::int64_t(dims_.x) * dims_.y;
  assert(t >= 0 && t < steps() && 0 <= z0 && z0 < z1 && z1 <= dims_.z &&
         std::int64_t(out.size()) == plane * (z1 - z0));
  {
    const std::lock_guard<std::mutex> lock(slab_reads_->m);
    ++slab_reads_->n;
  }
  slab_reads_->changed.notify_all();
  if (t == fail_at_)
    throw tsp::IoError(describe() + ": step " + std::to_string(t) + ": simulated read failure");
  std::copy(steps_[t].begin() + z0 * plane, steps_[t].begin() + z1 * plane, out.begin());
}

int MemorySource::slab_reads() const {
  const std::lock_guard<std::mutex> lock(slab_reads_->m);
  return slab_reads_->n;
}

void MemorySource::wait_for_slab_reads(int n) const {
  std::unique_lock<std::mutex> lock(slab_reads_->m);
  slab_reads_->changed.wait(lock, [&] { return slab_reads_->n >= n; });
}

}  // namespace tsptest

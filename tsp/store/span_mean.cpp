#include "tsp/store/span_mean.h"

#include <cassert>
#include <cstdint>
#include <vector>

namespace tsp {

BrickSamples span_mean(BrickCache& cache, int brick, int t0, int t1) {
  assert(0 <= t0 && t0 <= t1);
  if (t0 == t1) return cache.get(brick, t0);
  const bool stencil = cache.store().tree().has_stencil();
  const std::size_t n = std::size_t(cache.store().tree().octree().lattice(brick).count());
  const int mid = t0 + (t1 - t0) / 2;
  const BrickSamples middle = cache.get(brick, mid);
  assert(middle->size() == (stencil ? 2 * n : n));
  std::vector<std::uint64_t> sum(n, 0);
  std::vector<std::uint32_t> count(n, 0);
  for (int t = t0; t <= t1; ++t) {
    const BrickSamples s = t == mid ? middle : cache.get(brick, t);
    const std::uint16_t* codes = s->data();
    const std::uint16_t* inside = stencil ? codes + n : nullptr;
    for (std::size_t i = 0; i < n; ++i) {
      if (inside && inside[i] == 0) continue;
      sum[i] += codes[i];
      ++count[i];
    }
  }
  auto out = std::make_shared<std::vector<std::uint16_t>>(*middle);
  for (std::size_t i = 0; i < n; ++i)
    if (count[i] > 0) (*out)[i] = std::uint16_t((sum[i] + count[i] / 2) / count[i]);
  return out;
}

}  // namespace tsp

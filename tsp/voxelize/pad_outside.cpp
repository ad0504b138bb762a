#include <cstdint>
#include <vector>

#include "tsp/voxelize/voxelizer.h"

namespace tsp {

// Breadth-first from the inside voxels, each outside voxel takes the value of the inside voxel
// that reaches it first (voxelizer.h).
void pad_outside(std::span<float> values, std::span<const std::uint8_t> inside, Dims d) {
  const std::size_t n = values.size();
  const std::int64_t sx = 1, sy = d.x, sz = std::int64_t(d.x) * d.y;
  // The breadth-first search starts from the inside voxels on the boundary (those with an
  // outside neighbour), in index order; inside voxels deeper in are never reached from outside
  // before them.
  std::vector<std::int64_t> queue;
  std::vector<std::uint8_t> reached(inside.begin(), inside.end());
  for (std::size_t i = 0; i < n; ++i) {
    if (!inside[i]) continue;
    const std::int64_t j = std::int64_t(i);
    const int x = int(j % d.x), y = int(j / sy % d.y), z = int(j / sz);
    const bool edge = (x > 0 && !inside[i - 1]) || (x + 1 < d.x && !inside[i + 1]) ||
                      (y > 0 && !inside[std::size_t(j - sy)]) ||
                      (y + 1 < d.y && !inside[std::size_t(j + sy)]) ||
                      (z > 0 && !inside[std::size_t(j - sz)]) ||
                      (z + 1 < d.z && !inside[std::size_t(j + sz)]);
    if (edge) queue.push_back(j);
  }
  if (queue.empty()) return;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::int64_t i = queue[head];
    const int x = int(i % d.x), y = int(i / sy % d.y), z = int(i / sz);
    const std::int64_t nb[6] = {x > 0 ? i - sx : -1,       x + 1 < d.x ? i + sx : -1,
                                y > 0 ? i - sy : -1,       y + 1 < d.y ? i + sy : -1,
                                z > 0 ? i - sz : -1,       z + 1 < d.z ? i + sz : -1};
    for (std::int64_t j : nb) {
      if (j < 0 || reached[std::size_t(j)]) continue;
      reached[std::size_t(j)] = 1;
      values[std::size_t(j)] = values[std::size_t(i)];
      queue.push_back(j);
    }
  }
}

}  // namespace tsp

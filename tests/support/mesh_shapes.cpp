#include "support/mesh_shapes.h"

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace tsptest {

tsp::Mesh hex_box(int n, unsigned seed) {
  tsp::Mesh m;
  const int np = (n + 1) * (n + 1) * (n + 1);
  std::vector<std::int64_t> id(static_cast<std::size_t>(np));
  std::iota(id.begin(), id.end(), 0);
  std::mt19937 rng(seed);
  std::shuffle(id.begin(), id.end(), rng);
  m.points.resize(std::size_t(3 * np));
  m.values.resize(std::size_t(np));
  auto at = [&](int x, int y, int z) { return id[std::size_t(x + (n + 1) * (y + (n + 1) * z))]; };
  for (int z = 0; z <= n; ++z)
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x) {
        const std::int64_t p = at(x, y, z);
        m.points[std::size_t(3 * p)] = x;
        m.points[std::size_t(3 * p + 1)] = y;
        m.points[std::size_t(3 * p + 2)] = z;
        m.values[std::size_t(p)] = float(x);
      }
  m.offsets.push_back(0);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        for (auto p : {at(x, y, z), at(x + 1, y, z), at(x + 1, y + 1, z), at(x, y + 1, z),
                       at(x, y, z + 1), at(x + 1, y, z + 1), at(x + 1, y + 1, z + 1),
                       at(x, y + 1, z + 1)})
          m.connectivity.push_back(p);
        m.offsets.push_back(std::int64_t(m.connectivity.size()));
        m.types.push_back(tsp::CellType::hexahedron);
      }
  tsp::check_mesh(m, "hex box");
  return m;
}

}  // namespace tsptest

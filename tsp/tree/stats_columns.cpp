#include "tsp/tree/stats_columns.h"

#include <cassert>

namespace tsp {

StatsColumns stats_columns(const TspTree& tree) {
  const std::size_t n = std::size_t(tree.size());
  StatsColumns c{std::vector<double>(n), std::vector<double>(n), std::vector<float>(n),
                 std::vector<float>(n),  std::vector<float>(n),  std::vector<float>(n)};
  for (std::size_t i = 0; i < n; ++i) {
    const NodeStats& s = tree.stats(int(i));
    c.mean[i] = s.mean;
    c.std[i] = s.std;
    c.min[i] = s.min;
    c.max[i] = s.max;
    c.spatial_error[i] = s.spatial_error;
    c.temporal_error[i] = s.temporal_error;
  }
  return c;
}

void set_stats(TspTree& tree, const StatsColumns& c) {
  const std::size_t n = std::size_t(tree.size());
  assert(c.mean.size() == n && c.std.size() == n && c.min.size() == n && c.max.size() == n &&
         c.spatial_error.size() == n && c.temporal_error.size() == n);
  for (std::size_t i = 0; i < n; ++i) {
    NodeStats& s = tree.stats(int(i));
    s.mean = c.mean[i];
    s.std = c.std[i];
    s.min = c.min[i];
    s.max = c.max[i];
    s.spatial_error = c.spatial_error[i];
    s.temporal_error = c.temporal_error[i];
  }
}

}  // namespace tsp

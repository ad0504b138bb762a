#include "tsp/tree/tsp_tree.h"

#include <cassert>
#include <cmath>

#include "tsp/core/error.h"

namespace tsp {

namespace {
// The time tree, after checking the step count and the TSP node count for these dims.
TimeTree checked_time_tree(const Octree& octree, int steps) {
  if (steps < 1 || steps > kMaxSteps)
    throw UsageError(std::to_string(steps) + " time steps, expected 1 to " +
                     std::to_string(kMaxSteps));
  const std::int64_t nodes = std::int64_t(octree.size()) * (2 * std::int64_t(steps) - 1);
  if (nodes > kMaxTspNodes)
    throw UsageError(to_string(octree.dims()) + " x " + std::to_string(steps) + " steps needs " +
                     std::to_string(nodes) + " TSP nodes, at most " +
                     std::to_string(kMaxTspNodes) + " are supported (use larger bricks)");
  return TimeTree(steps);
}
}  // namespace

TspTree::TspTree(Dims dims, int steps, int brick_size)
    : octree_(dims, brick_size),
      time_(checked_time_tree(octree_, steps)),
      stats_(std::size_t(octree_.size()) * time_.size()),
      level_error_(std::size_t(octree_.level_brick_count()) * time_.steps(), 0.f) {}

ValueRange step_value_range(const TspTree& tree, int t) {
  assert(t >= 0 && t < tree.time().steps());
  const NodeStats& s = tree.stats(tree.id(0, tree.time().leaf_of(t)));
  if (s.empty() || !(s.min < s.max)) return tree.value_range();
  return {s.min, s.max};
}

double coefficient_of_variation(double sigma, double mean, double range_width) {
  if (sigma == 0) return 0;
  if (mean != 0) return sigma / std::fabs(mean);
  return range_width > 0 ? sigma / range_width : 0;
}

std::uint16_t Quantizer::encode(float v) const {
  double w = range.hi - range.lo;
  if (!(w > 0)) return 0;
  double q = std::nearbyint((double(v) - range.lo) / w * kQuantMax);
  if (!(q > 0)) return 0;  // also catches NaN
  if (q > kQuantMax) return kQuantMax;
  return std::uint16_t(q);
}

}  // namespace tsp

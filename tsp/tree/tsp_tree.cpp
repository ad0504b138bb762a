#include "tsp/tree/tsp_tree.h"

#include <cmath>

namespace tsp {

TspTree::TspTree(Dims dims, int steps, int brick_size)
    : octree_(dims, brick_size), time_(steps), stats_(std::size_t(octree_.size()) * time_.size()) {}

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

// Mergeable running statistics (count, mean, M2, min, max) for the builder's node statistics.
// Groups are combined with Chan et al.'s pairwise update, never with Σv² − (Σv)²/N, so the
// variance of large groups of nearly equal values keeps its digits.
#pragma once
#include <cmath>
#include <cstdint>
#include <limits>

#include "tsp/tree/tsp_tree.h"

namespace tsp {

/// Count, mean, sum of squared deviations (M2) and extremes of a group of samples.
struct Moments {
  double n = 0;     ///< number of samples
  double mean = 0;  ///< mean of the samples
  double m2 = 0;    ///< Σ (v − mean)²
  float min = std::numeric_limits<float>::infinity();
  float max = -std::numeric_limits<float>::infinity();

  /// Adds one sample (Welford's update); never throws.
  void add(float v) {
    n += 1;
    double d = double(v) - mean;
    mean += d / n;
    m2 += d * (double(v) - mean);
    min = std::fmin(min, v);
    max = std::fmax(max, v);
  }
  /// Adds another group (Chan et al.); never throws.
  void merge(const Moments& o) {
    if (o.n == 0) return;
    if (n == 0) {
      *this = o;
      return;
    }
    double total = n + o.n;
    double d = o.mean - mean;
    mean += d * (o.n / total);
    m2 += o.m2 + d * d * (n * o.n / total);
    n = total;
    min = std::fmin(min, o.min);
    max = std::fmax(max, o.max);
  }
  /// Population standard deviation sqrt(M2 / n); 0 for an empty group.
  double std_dev() const { return n > 0 ? std::sqrt(std::fmax(m2, 0.0) / n) : 0.0; }
};

/// Everything a TSP node's statistics are made of, mergeable across octree children.
struct NodeAccum {
  Moments moments;          ///< over all n·m samples of the node
  double cov_sum = 0;       ///< Σᵢ COV(σᵢ, v̄ᵢ) over the node's voxels (numerator of e_st)
  std::int64_t voxels = 0;  ///< n, own voxels of the octree node

  /// Adds a disjoint set of voxels over the same span; never throws.
  void merge(const NodeAccum& o) {
    moments.merge(o.moments);
    cov_sum += o.cov_sum;
    voxels += o.voxels;
  }
  /// Final statistics with the spec's COV rule, range_width being the quantization range width.
  NodeStats finish(double range_width) const {
    NodeStats s;
    s.mean = moments.mean;
    s.std = moments.std_dev();
    // No voxel (all outside a stencil): the empty marker min > max.
    s.min = moments.n > 0 ? moments.min : std::numeric_limits<float>::infinity();
    s.max = moments.n > 0 ? moments.max : -std::numeric_limits<float>::infinity();
    s.spatial_error = float(coefficient_of_variation(s.std, s.mean, range_width));
    s.temporal_error = voxels > 0 ? float(cov_sum / double(voxels)) : 0.f;
    return s;
  }
};

}  // namespace tsp

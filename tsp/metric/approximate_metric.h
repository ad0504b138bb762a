// Per-node evaluation of the TF-dependent metrics that use only stored statistics: approximate
// colour (TSP paper eqs. 14–20) and perceptual (the same in CIE L*u*v*, spec §4 "beyond"), and
// the scalar metric with the transparency test and an estimated mean colour.
#pragma once
#include <vector>

#include "tsp/metric/metric.h"

namespace tsp {

/// Tables derived from one transfer-function version (built once per edit, O(K)), and the
/// per-node kernel, O(j_max − j_min). Immutable after construction: evaluate() is thread-safe.
class ApproximateMetric {
 public:
  /// Prepares metric (scalar, approximate or perceptual; asserts on reference) for tf.
  ApproximateMetric(Metric metric, const TransferFunction& tf);
  /// The node's errors, estimated mean colour and exact transparency flag.
  NodeResult evaluate(const NodeStats& stats) const;
  /// The TF variation V = sqrt(Σ_{j<K−1} d(c(j), c(j+1))) of eq. 20, in the metric's space.
  double variation() const { return variation_; }
  /// The transfer-function version the tables were built from.
  std::uint64_t tf_version() const { return version_; }
  /// The metric.
  Metric metric() const { return metric_; }
  /// [j_min, j_max] of a node under the tables' transfer function.
  EntryRange entry_range(const NodeStats& stats) const;

 private:
  struct Entry {
    double c[4];    // coordinates d() works in: r, g, b (or L*, u*, v* / 100) and α
    double rgb[3];  // sRGB for the reported mean colour
  };
  Metric metric_;
  std::uint64_t version_;
  ValueRange domain_;
  std::vector<int> opaque_prefix_;  // opaque_prefix_[j] = #entries below j with α > 0
  std::vector<Entry> entries_;
  std::vector<double> step_distance_;  // d(c(j), c(j+1)), K − 1 values
  double variation_ = 0;
};

}  // namespace tsp

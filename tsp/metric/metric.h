// tsp/metric: transfer functions and the four error metrics (spec §4) a TF edit recomputes —
// scalar, reference colour, approximate colour and perceptual. This header holds the types they
// share: which metric, and each TSP node's e_s, e_t, mean colour and exact transparency flag
// (spec §3). May include core/, tree/ and store/ (brick data for the reference metric).
// Formulas and our rules: docs/metrics.md.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "tsp/metric/transfer_function.h"
#include "tsp/tree/traversal.h"
#include "tsp/tree/tsp_tree.h"

namespace tsp {

/// Which error metric to compute.
enum class Metric { scalar, reference, approximate, perceptual };

/// "scalar", "reference", "approximate" or "perceptual".
const char* to_string(Metric m);
/// Parses a metric name. Throws UsageError naming the accepted names.
Metric parse_metric(const std::string& name);

/// One TSP node's result under one metric and transfer function.
struct NodeResult {
  float spatial = 0;   ///< e_s (0 for transparent nodes)
  float temporal = 0;  ///< e_t (0 for transparent nodes)
  Rgba mean;  ///< mean colour (estimated for scalar/approximate/perceptual); 0 if transparent
  bool transparent = false;  ///< max α over the node's [j_min, j_max] is 0
};

/// Every TSP node's result, indexed by TSP node id.
struct MetricResult {
  Metric metric = Metric::scalar;
  NodeErrors errors;                      ///< e_s, e_t per node
  std::vector<Rgba> mean_colour;          ///< per node
  std::vector<std::uint8_t> transparent;  ///< per node, 1 = transparent
  /// Number of transparent nodes.
  std::int64_t transparent_count() const;
};

/// [j_min, j_max] of a node: the TF entries of its min and max scalar.
struct EntryRange {
  int lo = 0, hi = 0;
};
/// Entries of stats.min and stats.max in tf.
EntryRange entry_range(const TransferFunction& tf, const NodeStats& stats);

}  // namespace tsp

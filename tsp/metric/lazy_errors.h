// Live recompute after transfer-function edits (spec §4): the approximate and perceptual errors
// (and the scalar metric's transparency) evaluated on demand, memoised per TF version, so an
// edit costs only the nodes the next traversal visits. See docs/metrics.md.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "tsp/metric/approximate_metric.h"
#include "tsp/metric/frame_metric.h"
#include "tsp/metric/metric.h"

namespace tsp {

/// Memoised per-node errors for one tree and one (editable) transfer function; serves frames as
/// a FrameMetric. Not thread-safe (all() runs its own workers inside).
class LazyErrors final : public FrameMetric {
 public:
  /// metric must be scalar, approximate or perceptual (UsageError for reference, which needs
  /// the bricks: use ReferenceMetric). tf is held by reference and must outlive this object;
  /// its edits are noticed through its version.
  LazyErrors(const TspTree& tree, Metric metric, const TransferFunction& tf);
  /// Switches to another transfer function object (every node is recomputed on demand).
  void set_transfer_function(const TransferFunction& tf);

  /// Result of TSP node id under the current TF version; evaluated at most once per node and
  /// version, and kept across edits that do not touch the node's [j_min, j_max].
  const NodeResult& node(int id);
  /// Makes every node a traversal of step t can visit current (for each octree node, the time
  /// nodes on the path from the root to step t's leaf) and returns the error vectors; entries
  /// of other nodes may be stale. Asserts 0 ≤ t < steps.
  const NodeErrors& errors_for_step(int t) override;
  /// Makes every node current with `threads` workers (0 = all cores) and returns the errors.
  const NodeErrors& all(int threads = 0);
  /// all() on every core.
  const NodeErrors& all_errors() override { return all(); }
  /// e_s and transparency of a node made current by errors_for_step() or all() (asserted).
  NodeClassInfo class_info(int id) const override;
  /// Mean colour of a node made current by errors_for_step() or all() (asserted).
  Rgba mean_colour(int id) const override;

  /// Node evaluations performed so far (for tests and benchmarks).
  std::int64_t evaluations() const { return evaluations_; }
  /// The metric.
  Metric metric() const { return metric_; }

 private:
  static constexpr std::uint64_t kNever = ~std::uint64_t(0);
  const TspTree& tree_;
  Metric metric_;
  const TransferFunction* tf_;
  std::unique_ptr<ApproximateMetric> tables_;  // for the TF version being served
  std::vector<NodeResult> results_;
  std::vector<std::uint64_t> stamp_;  // TF version results_[id] is valid for, or kNever
  NodeErrors errors_;
  std::int64_t evaluations_ = 0;
  void sync();
  bool refresh(int id);  // brings node id up to date; true when it had to be evaluated
};

}  // namespace tsp

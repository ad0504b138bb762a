// What one frame reads of the current metric and transfer function, whichever metric it is: the
// errors its traversal compares with the tolerances, and per node the class inputs (e_s,
// transparency) and the mean colour a flat node is drawn in. A whole-tree MetricResult and the
// live LazyErrors both serve it, so the renderer and the player have one path for both.
#pragma once
#include "tsp/metric/metric.h"

namespace tsp {

/// What the frame plan needs of one TSP node under the current metric and transfer function.
struct NodeClassInfo {
  float spatial = 0;         ///< e_s
  bool transparent = false;  ///< max α over [j_min, j_max] is 0
};

/// Per-node errors, classes and colours for frames. Not thread-safe: one frame at a time.
class FrameMetric {
 public:
  virtual ~FrameMetric() = default;
  /// The error table step's traversal reads; makes every node that traversal can visit current
  /// (a live metric evaluates them). Asserts 0 ≤ step < steps; throws what the metric throws.
  virtual const NodeErrors& errors_for_step(int step) = 0;
  /// The error table with every node current (for work over all steps, e.g. which textures any
  /// frame can still draw). Throws what the metric throws.
  virtual const NodeErrors& all_errors() = 0;
  /// e_s and transparency of TSP node id; valid for the nodes the last errors_for_step() or
  /// all_errors() made current. Never throws.
  virtual NodeClassInfo class_info(int tsp_id) const = 0;
  /// Mean colour (not premultiplied) of TSP node id, with the same validity. Never throws.
  virtual Rgba mean_colour(int tsp_id) const = 0;
};

/// A FrameMetric over a computed MetricResult, which must outlive it (every node is current).
class WholeTreeMetric final : public FrameMetric {
 public:
  /// Serves m.
  explicit WholeTreeMetric(const MetricResult& m) : m_(m) {}
  /// m's errors.
  const NodeErrors& errors_for_step(int) override { return m_.errors; }
  /// m's errors.
  const NodeErrors& all_errors() override { return m_.errors; }
  /// From m's e_s and transparency flag.
  NodeClassInfo class_info(int id) const override {
    return {m_.errors.spatial[std::size_t(id)], m_.transparent[std::size_t(id)] != 0};
  }
  /// m's mean colour.
  Rgba mean_colour(int id) const override { return m_.mean_colour[std::size_t(id)]; }

 private:
  const MetricResult& m_;
};

}  // namespace tsp

// tsp/tree: the TSP tree's shape, statistics and traversal, no data and no files; may include
// core/.
// The TSP tree: octree skeleton × one binary time tree per octree node, with every node's
// statistics (spec §2). A TSP node id is octree_id · (2T − 1) + time_id.
#pragma once
#include <span>
#include <vector>

#include "tsp/core/types.h"
#include "tsp/tree/octree.h"
#include "tsp/tree/time_tree.h"

namespace tsp {

/// Statistics of one TSP node over its n voxels × m steps, in data units (spec §2).
struct NodeStats {
  double mean = 0;            ///< v̄ over all N = n·m samples
  double std = 0;             ///< σ over all samples (population form, 1/N)
  float min = 0, max = 0;     ///< extreme sample values
  float spatial_error = 0;    ///< e_ss = σ / |v̄| with the spec's COV rule
  float temporal_error = 0;   ///< e_st = (1/n) Σᵢ σᵢ / |v̄ᵢ| with the same rule per voxel
  /// True when no voxel of the node lies inside the data (a stencil's outside; min > max then):
  /// such a node is never drawn.
  bool empty() const { return min > max; }
};

/// The whole tree: shape plus statistics for every (octree node, time node) pair.
class TspTree {
 public:
  /// An empty-statistics tree for a dims grid, `steps` steps and brick_size bricks.
  /// Throws UsageError on an invalid brick size or grid.
  TspTree(Dims dims, int steps, int brick_size);
  /// Spatial skeleton.
  const Octree& octree() const { return octree_; }
  /// Ends the data at the flagged octree nodes (Octree::stop_at). Throws UsageError.
  void stop_at(std::span<const std::uint8_t> flags) { octree_.stop_at(flags); }
  /// Time-tree shape shared by every octree node.
  const TimeTree& time() const { return time_; }
  /// Number of TSP nodes, octree().size() · time().size().
  int size() const { return int(stats_.size()); }
  /// TSP node id of (octree node, time node).
  int id(int octree_id, int time_id) const { return octree_id * time_.size() + time_id; }
  /// Octree node of TSP node id.
  int octree_of(int id) const { return id / time_.size(); }
  /// Time node of TSP node id.
  int time_of(int id) const { return id % time_.size(); }
  /// Statistics of TSP node id.
  const NodeStats& stats(int id) const { return stats_[id]; }
  /// Mutable statistics, for the builder and the file reader.
  NodeStats& stats(int id) { return stats_[id]; }
  /// All statistics, indexed by TSP node id.
  std::span<const NodeStats> all_stats() const { return stats_; }
  /// Value range in data units that the quantized bricks map onto [0, kQuantMax].
  ValueRange value_range() const { return range_; }
  /// Sets the quantization range.
  void set_value_range(ValueRange r) { range_ = r; }
  /// Level error of octree node o at step t: the RMS difference, in data units, between the
  /// node's voxels and their trilinear reconstruction from its level brick (0 for leaves).
  float level_error(int o, int t) const {
    const int i = octree_.node_brick(o) - octree_.brick_count();
    return i < 0 ? 0.f : level_error_[std::size_t(i) * time_.steps() + t];
  }
  /// True when the tree's volume has a stencil (voxels outside the data).
  bool has_stencil() const { return !inside_.empty(); }
  /// Fraction of octree node o's own voxels inside the data, over the whole series (1 without
  /// a stencil). A node with a fraction below 1 is never drawn flat.
  float inside_fraction(int o) const { return inside_.empty() ? 1.f : inside_[std::size_t(o)]; }
  /// Sets the inside fractions, one per octree node (empty: no stencil).
  void set_inside_fractions(std::vector<float> f) { inside_ = std::move(f); }
  /// The inside fractions by octree node (empty without a stencil).
  std::span<const float> inside_fractions() const { return inside_; }
  /// All level errors, [level brick][step] (level brick = stored brick − brick_count()).
  std::span<const float> level_errors() const { return level_error_; }
  /// Mutable level errors, for the builder and the file reader.
  std::span<float> level_errors() { return level_error_; }

 private:
  Octree octree_;
  TimeTree time_;
  std::vector<NodeStats> stats_;
  std::vector<float> level_error_;
  std::vector<float> inside_;
  ValueRange range_;
};

/// The extreme sample values of step t over the whole volume (the statistics of the root's leaf
/// time node for t); the tree's value_range() when the step holds no sample inside the data.
/// Asserts 0 <= t < steps.
ValueRange step_value_range(const TspTree& tree, int t);

/// COV with the spec's rule: 0 when sigma = 0; sigma / |mean| when mean ≠ 0; otherwise
/// sigma / range_width (and 0 when that width is 0 too).
double coefficient_of_variation(double sigma, double mean, double range_width);

/// 16-bit linear quantization over a value range: v = lo + q·(hi − lo)/65535.
struct Quantizer {
  ValueRange range;
  /// Nearest code for v, clamped to [0, kQuantMax] (a zero-width range maps to 0).
  std::uint16_t encode(float v) const;
  /// Value of code q in data units.
  float decode(std::uint16_t q) const {
    return float(range.lo + double(q) * (range.hi - range.lo) / kQuantMax);
  }
};

}  // namespace tsp

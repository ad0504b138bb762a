// tsp/lod: the spatial LOD cut over the octree's level bricks (spec §14, papers 000 §5 and 002) —
// the cut, its errors, the frame-time cost model and the controller that adapts the cut every
// frame; may include core/, tree/, metric/ and frame/.
// The active cut: a set of octree nodes that covers the volume exactly once; each draws its own
// brick (a leaf's, or an internal node's level brick). The TSP tree still decides, on every cut
// node, whether it is skipped, drawn flat or textured from a span (tsp/tree/traversal.h).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "tsp/tree/marks.h"
#include "tsp/tree/octree.h"

namespace tsp {

/// Bytes of one brick texture as the cut counts them: the padded stored brick (the atlas slot),
/// 2 bytes per sample. Never throws.
std::int64_t brick_slot_bytes(const Octree& octree);

/// A cut through an octree. Not thread-safe; copyable.
class LodCut {
 public:
  /// The coarsest cut: the root alone.
  explicit LodCut(const Octree& octree);
  /// The cut of nodes at LOD level k (0 = full resolution): every node with lod_level ≤ k whose
  /// parent's level is above k (the root when k ≥ its level). Asserts k ≥ 0.
  static LodCut at_level(const Octree& octree, int k);
  /// True when node id is in the cut.
  bool contains(int id) const { return in_[std::size_t(id)] != LodStop::none; }
  /// The traversal's LodStops: LodStop::cut on the cut's nodes, none elsewhere.
  LodStops stops() const { return in_; }
  /// The nodes in the cut, in node order.
  std::vector<int> nodes() const;
  /// Number of nodes in the cut.
  int size() const { return size_; }
  /// True when id is in the cut and has children.
  bool can_split(int id) const;
  /// True when id is not in the cut and all its children are.
  bool can_merge(int id) const;
  /// Replaces id by its children; asserts can_split(id).
  void split(int id);
  /// Replaces id's children by id; asserts can_merge(id).
  void merge(int id);
  /// The cut's bricks' bytes: one brick slot per node.
  std::int64_t texture_bytes() const { return std::int64_t(size_) * brick_slot_bytes(*octree_); }
  /// Cut nodes per LOD level, index = level (max_lod_level() + 1 entries).
  std::vector<int> nodes_per_level() const;
  /// True when every leaf brick has exactly one cut node among itself and its ancestors (the cut
  /// covers the volume exactly once). O(bricks · depth).
  bool covers_once() const;

 private:
  const Octree* octree_;
  std::vector<LodStop> in_;  // per octree node: cut or none
  int size_ = 0;
};

}  // namespace tsp

// TSP tree traversal (spec §5, paper Fig. 2) and back-to-front child order (spec §6).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "tsp/tree/marks.h"
#include "tsp/tree/tsp_tree.h"

namespace tsp {

/// User error tolerances compared with each node's e_s and e_t.
struct Tolerances {
  double spatial = 0;
  double temporal = 0;
  /// Both equal.
  bool operator==(const Tolerances&) const = default;
};

/// Per-TSP-node errors the traversal compares with the tolerances (any metric).
struct NodeErrors {
  std::vector<float> spatial;   ///< e_s, indexed by TSP node id
  std::vector<float> temporal;  ///< e_t, indexed by TSP node id
};

/// The scalar metric's errors (e_ss, e_st) copied out of the tree's statistics.
NodeErrors scalar_errors(const TspTree& tree);

/// One node the traversal emits: draw octree node `octree_id` with the data of time node
/// `time_id`, whose span holds the current step.
struct Emitted {
  int octree_id = -1;
  int time_id = -1;
  Span span;
  /// With clip sides: kept whole, removed (drawn nowhere), or straddles the clip surface (a
  /// leaf or LOD cut node; drawn textured and clipped per sample).
  ClipSide clip = ClipSide::kept;
  bool operator==(const Emitted&) const = default;
};

/// Chooses the order of an octree node's children, farthest first. Voxel coordinates: sample
/// i along an axis lies at coordinate i, so a node's split plane along axis a is its upper
/// child's box.lo[a] (also the lower child's shared last sample layer).
class ViewOrder {
 public:
  /// Orthographic view looking along dir (from the eye into the scene), voxel coordinates.
  static ViewOrder orthographic(std::array<double, 3> dir);
  /// Perspective view from eye, in voxel coordinates.
  static ViewOrder perspective(std::array<double, 3> eye);
  /// The octant (bit a set = upper half along axis a) to visit first below node id; bits of
  /// axes the node does not split are 0, so the octant is an existing child (0 for a leaf).
  int farthest_octant(const Octree& octree, int id) const;
  /// True for a perspective view.
  bool is_perspective() const { return perspective_; }

 private:
  bool perspective_ = false;
  std::array<double, 3> v_{0, 0, 1};
};

/// An octree node's existing children in back-to-front order; ids[0, count) are valid.
struct ChildOrder {
  std::array<int, 8> ids{-1, -1, -1, -1, -1, -1, -1, -1};
  int count = 0;
};

/// Children of octree node id farthest first: octants f^0, f^1, …, f^7 (XOR order) with
/// f = view.farthest_octant(octree, id), absent ones skipped. Empty for a leaf.
ChildOrder back_to_front_children(const Octree& octree, int id, const ViewOrder& view);

/// Per TSP node id, true when the node is transparent under the current TF over its span (the
/// metric's class). Empty: unknown.
using TransparentFn = std::function<bool(int tsp_id)>;

/// What one traversal reads: the tree, the step, the tolerances, the errors table, the view and
/// the optional per-node marks. tree and errors are referenced and must outlive the call.
struct TraversalQuery {
  const TspTree& tree;             ///< the tree to walk
  int step = 0;                    ///< the current step t, 0 ≤ t < steps
  Tolerances tol;                  ///< compared with each node's errors
  const NodeErrors& errors;        ///< e_s and e_t per TSP node id (tree.size() entries each)
  ViewOrder view;                  ///< the children's back-to-front order
  LodStops stops = {};             ///< empty, or per octree node: end the descent there (LOD cut)
  ClipSides clip = {};             ///< empty, or per octree node: its side of the clip surface
  TransparentFn transparent = {};  ///< empty: the paper's rule; else our rule (below)
};

/// Traverses q.tree for step q.step and returns the emitted nodes in back-to-front order.
/// The emitted octree nodes tile the volume exactly once. With stops, a node marked there is
/// treated as a leaf (any LodStop other than none): emitted with the largest temporally coherent
/// span (or its leaf span) when no coherent span holds it whole. With clip sides, a node clipped
/// away is emitted as such (ClipSide::removed, its time leaf: drawn nowhere, but it tiles the
/// volume like the others), and a node across the clip surface is never drawn whole above the
/// leaves or the cut (the descent goes on; ClipSide::straddles at a leaf or cut node). With
/// transparent (issue 9 item 5, our rule), a coherent node above the leaves and the cut that is not
/// transparent itself but has a transparent child (at the same time node) is not emitted: the
/// descent goes on, so what zero tolerance skips is never drawn; empty: the paper's rule. Asserts 0
/// ≤ step < steps, that errors hold tree.size() entries each, and that stops and clip are empty or
/// have one entry per octree node. Never throws.
std::vector<Emitted> traverse(const TraversalQuery& q);

}  // namespace tsp

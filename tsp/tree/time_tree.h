// The binary time tree shared by every octree node: root [0, T−1], split at ⌊(t1+t2)/2⌋.
#pragma once
#include <vector>

#include "tsp/core/types.h"

namespace tsp {

/// Shape of the binary time tree over T steps; nodes are numbered breadth-first, root = 0.
class TimeTree {
 public:
  /// Builds the tree over `steps` ≥ 1 steps (asserts on fewer).
  explicit TimeTree(int steps);
  /// Number of steps T.
  int steps() const { return steps_; }
  /// Number of time nodes, 2T − 1.
  int size() const { return int(nodes_.size()); }
  /// Span [t1, t2] of node id.
  Span span(int id) const { return nodes_[id].span; }
  /// Left child ([t1, mid]) or −1 for a leaf.
  int left(int id) const { return nodes_[id].left; }
  /// Right child ([mid+1, t2]) or −1 for a leaf.
  int right(int id) const { return nodes_[id].right; }
  /// Parent, −1 for the root.
  int parent(int id) const { return nodes_[id].parent; }
  /// Depth below the root (root = 0).
  int level(int id) const { return nodes_[id].level; }
  /// True for single-step nodes.
  bool is_leaf(int id) const { return nodes_[id].left < 0; }
  /// The leaf whose span is [t, t].
  int leaf_of(int t) const { return leaf_of_[t]; }
  /// The child of id whose span holds t (id must not be a leaf and must hold t).
  int child_holding(int id, int t) const;
  /// Largest level in the tree.
  int depth() const { return depth_; }

 private:
  struct Node {
    Span span;
    int left = -1, right = -1, parent = -1, level = 0;
  };
  int steps_;
  int depth_ = 0;
  std::vector<Node> nodes_;
  std::vector<int> leaf_of_;
};

}  // namespace tsp

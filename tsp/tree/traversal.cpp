#include "tsp/tree/traversal.h"

#include <cassert>
#include <utility>

namespace tsp {

NodeErrors scalar_errors(const TspTree& tree) {
  NodeErrors e;
  e.spatial.reserve(tree.size());
  e.temporal.reserve(tree.size());
  for (const NodeStats& s : tree.all_stats()) {
    e.spatial.push_back(s.spatial_error);
    e.temporal.push_back(s.temporal_error);
  }
  return e;
}

ViewOrder ViewOrder::orthographic(std::array<double, 3> dir) {
  ViewOrder v;
  v.perspective_ = false;
  v.v_ = dir;
  return v;
}

ViewOrder ViewOrder::perspective(std::array<double, 3> eye) {
  ViewOrder v;
  v.perspective_ = true;
  v.v_ = eye;
  return v;
}

int ViewOrder::farthest_octant(const Octree& octree, int id) const {
  const OctreeNode& n = octree.node(id);
  int f = 0;
  for (int a = 0; a < 3; ++a) {
    // The child in octant (1 << a) exists exactly when the node splits axis a.
    const int upper = n.children[1 << a];
    if (upper < 0) continue;
    bool upper_is_farther;
    if (perspective_) {
      // The half not containing the eye is farther; an eye on the plane sees either half
      // without looking through the other, so ties may go either way.
      upper_is_farther = v_[a] < octree.node(upper).box.lo[a];
    } else {
      upper_is_farther = v_[a] > 0;
    }
    if (upper_is_farther) f |= 1 << a;
  }
  return f;
}

ChildOrder back_to_front_children(const Octree& octree, int id, const ViewOrder& view) {
  ChildOrder order;
  const OctreeNode& n = octree.node(id);
  if (n.is_leaf()) return order;
  const int f = view.farthest_octant(octree, id);
  // XOR order: for any two children the highest differing bit of k puts the earlier one on
  // the far side of that axis' split plane, so the plane separates it from the eye's side.
  for (int k = 0; k < 8; ++k) {
    const int child = n.children[f ^ k];
    if (child >= 0) order.ids[order.count++] = child;
  }
  return order;
}

namespace {

constexpr int kFailed = -1;

// Paper Fig. 2 for one step: a recursive octree walk that asks each node's time tree for
// the largest coherent span holding t.
class Walker {
 public:
  Walker(const TspTree& tree, int t, const Tolerances& tol, const NodeErrors& errors,
         const ViewOrder& view, LodStops stops, ClipSides clip, const TransparentFn& transparent)
      : tree_(tree), t_(t), tol_(tol), errors_(errors), view_(view), stops_(stops), clip_(clip),
        transparent_(transparent) {}

  void visit(int o) {
    const ClipSide side = clip_.empty() ? ClipSide::kept : clip_[std::size_t(o)];
    if (side == ClipSide::removed) {  // clipped away: nothing of it is drawn
      emit(o, tree_.time().leaf_of(t_), side);
      return;
    }
    const bool leaf = tree_.octree().node(o).is_leaf();
    const bool stop = leaf || (!stops_.empty() && stops_[std::size_t(o)] != LodStop::none);
    // Across the clip surface: drawn only per sample, so never whole above a leaf or cut node.
    int tau = side == ClipSide::straddles && !stop ? kFailed : coherent_time_node(o, leaf);
    if (tau == kFailed && stop && !leaf) tau = coherent_time_node(o, true);
    // Our rule: a coherent node holding a transparent child is drawn as its children, so the
    // transparent part is skipped as at zero tolerance instead of drawn in the node's mean.
    if (tau != kFailed && !stop && transparent_ && has_transparent_child(o, tau)) tau = kFailed;
    if (tau != kFailed) {
      emit(o, tau, side);
    } else if (stop) {
      emit(o, tree_.time().leaf_of(t_), side);
    } else {
      ChildOrder kids = back_to_front_children(tree_.octree(), o, view_);
      for (int i = 0; i < kids.count; ++i) visit(kids.ids[i]);
    }
  }

  std::vector<Emitted> take() { return std::move(out_); }

 private:
  // timetree_traverse: walk from the time root towards t, return the first time node
  // that is coherent enough, or kFailed.
  int coherent_time_node(int o, bool octree_leaf) const {
    const TimeTree& time = tree_.time();
    int tau = 0;
    for (;;) {
      const int id = tree_.id(o, tau);
      if (double(errors_.temporal[id]) <= tol_.temporal &&
          (octree_leaf || double(errors_.spatial[id]) <= tol_.spatial))
        return tau;
      if (time.is_leaf(tau)) return kFailed;
      tau = time.child_holding(tau, t_);
    }
  }

  // True when o at time node tau is not transparent but one of its children is.
  bool has_transparent_child(int o, int tau) const {
    if (transparent_(tree_.id(o, tau))) return false;
    for (int c : tree_.octree().node(o).children)
      if (c >= 0 && transparent_(tree_.id(c, tau))) return true;
    return false;
  }

  void emit(int o, int tau, ClipSide side) {
    out_.push_back(Emitted{o, tau, tree_.time().span(tau), side});
  }

  const TspTree& tree_;
  int t_;
  const Tolerances& tol_;
  const NodeErrors& errors_;
  const ViewOrder& view_;
  LodStops stops_;
  ClipSides clip_;
  const TransparentFn& transparent_;
  std::vector<Emitted> out_;
};

}  // namespace

std::vector<Emitted> traverse(const TraversalQuery& q) {
  assert(q.step >= 0 && q.step < q.tree.time().steps());
  assert(int(q.errors.spatial.size()) == q.tree.size() &&
         int(q.errors.temporal.size()) == q.tree.size());
  assert(q.stops.empty() || int(q.stops.size()) == q.tree.octree().size());
  assert(q.clip.empty() || int(q.clip.size()) == q.tree.octree().size());
  Walker walker(q.tree, q.step, q.tol, q.errors, q.view, q.stops, q.clip, q.transparent);
  walker.visit(0);
  return walker.take();
}

}  // namespace tsp

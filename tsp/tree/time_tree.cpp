#include "tsp/tree/time_tree.h"

#include <algorithm>
#include <cassert>

namespace tsp {

TimeTree::TimeTree(int steps) : steps_(steps) {
  assert(steps >= 1);
  nodes_.reserve(2 * std::size_t(steps) - 1);
  leaf_of_.assign(steps, -1);
  nodes_.push_back(Node{Span{0, steps - 1}});
  // Breadth-first: children are appended while the queue (the vector itself) is walked.
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    Span s = nodes_[i].span;
    depth_ = std::max(depth_, nodes_[i].level);
    if (s.t0 == s.t1) {
      leaf_of_[s.t0] = int(i);
      continue;
    }
    int mid = (s.t0 + s.t1) / 2;
    int level = nodes_[i].level + 1;
    nodes_[i].left = int(nodes_.size());
    nodes_.push_back(Node{Span{s.t0, mid}, -1, -1, int(i), level});
    nodes_[i].right = int(nodes_.size());
    nodes_.push_back(Node{Span{mid + 1, s.t1}, -1, -1, int(i), level});
  }
}

int TimeTree::child_holding(int id, int t) const {
  assert(!is_leaf(id) && span(id).contains(t));
  int l = left(id);
  return span(l).contains(t) ? l : right(id);
}

}  // namespace tsp

#include "tsp/lod/lod_cut.h"

#include <cassert>

namespace tsp {

std::int64_t brick_slot_bytes(const Octree& octree) {
  const auto shape = octree.max_brick_samples();
  return std::int64_t(shape[0]) * shape[1] * shape[2] * std::int64_t(sizeof(std::uint16_t));
}

LodCut::LodCut(const Octree& octree)
    : octree_(&octree), in_(std::size_t(octree.size()), LodStop::none), size_(1) {
  in_[0] = LodStop::cut;
}

LodCut LodCut::at_level(const Octree& octree, int k) {
  assert(k >= 0);
  LodCut cut(octree);
  // Breadth-first order: parents come before their children, so one pass splits top-down.
  for (int id = 0; id < octree.size(); ++id)
    if (cut.contains(id) && octree.lod_level(id) > k && cut.can_split(id)) cut.split(id);
  return cut;
}

std::vector<int> LodCut::nodes() const {
  std::vector<int> out;
  out.reserve(std::size_t(size_));
  for (int id = 0; id < int(in_.size()); ++id)
    if (contains(id)) out.push_back(id);
  return out;
}

bool LodCut::can_split(int id) const { return contains(id) && !octree_->node(id).is_leaf(); }

bool LodCut::can_merge(int id) const {
  const OctreeNode& n = octree_->node(id);
  if (contains(id) || n.is_leaf()) return false;
  for (int c : n.children)
    if (c >= 0 && !contains(c)) return false;
  return true;
}

void LodCut::split(int id) {
  assert(can_split(id));
  in_[std::size_t(id)] = LodStop::none;
  --size_;
  for (int c : octree_->node(id).children)
    if (c >= 0) {
      in_[std::size_t(c)] = LodStop::cut;
      ++size_;
    }
}

void LodCut::merge(int id) {
  assert(can_merge(id));
  for (int c : octree_->node(id).children)
    if (c >= 0) {
      in_[std::size_t(c)] = LodStop::none;
      --size_;
    }
  in_[std::size_t(id)] = LodStop::cut;
  ++size_;
}

std::vector<int> LodCut::nodes_per_level() const {
  std::vector<int> n(std::size_t(octree_->max_lod_level() + 1), 0);
  for (int id = 0; id < int(in_.size()); ++id)
    if (contains(id)) ++n[std::size_t(octree_->lod_level(id))];
  return n;
}

bool LodCut::covers_once() const {
  for (int b = 0; b < octree_->brick_count(); ++b) {
    int hits = 0;
    for (int id = octree_->brick_node(b); id >= 0; id = octree_->node(id).parent)
      hits += contains(id);
    if (hits != 1) return false;
  }
  return true;
}

}  // namespace tsp

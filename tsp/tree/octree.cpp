#include "tsp/tree/octree.h"

#include <algorithm>

#include "tsp/core/error.h"

namespace tsp {

namespace {
bool is_power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }
}  // namespace

Octree::Octree(Dims dims, int brick_size) : dims_(dims), brick_size_(brick_size) {
  if (!is_power_of_two(brick_size) || brick_size < kMinBrickSize || brick_size > kMaxBrickSize)
    throw UsageError("brick size " + std::to_string(brick_size) + " is not a power of two in [" +
                     std::to_string(kMinBrickSize) + ", " + std::to_string(kMaxBrickSize) + "]");
  if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0)
    throw UsageError("grid size " + to_string(dims) + " has an empty axis");
  if (dims.x > kMaxGridEdge || dims.y > kMaxGridEdge || dims.z > kMaxGridEdge)
    throw UsageError("grid size " + to_string(dims) + ": every edge must be at most " +
                     std::to_string(kMaxGridEdge) + " samples");
  // As few bricks as B allows, with the cells spread evenly over them: a 64-sample axis becomes
  // 3 bricks of 21 cells rather than 31 + 31 + 2, so edge bricks are not slivers.
  const int max_cells = brick_size - 1;
  for (int a = 0; a < 3; ++a) {
    const int cells = dims[a] - 1;
    grid_[a] = std::max(1, (cells + max_cells - 1) / max_cells);
    cells_[a] = std::max(1, (cells + grid_[a] - 1) / grid_[a]);
  }
  const std::int64_t bricks = std::int64_t(grid_[0]) * grid_[1] * grid_[2];
  if (bricks > kMaxBricks)
    throw UsageError("grid size " + to_string(dims) + " with bricks of " +
                     std::to_string(brick_size) + " needs " + std::to_string(bricks) +
                     " bricks, at most " + std::to_string(kMaxBricks) +
                     " are supported (use larger bricks)");
  brick_node_.assign(std::size_t(bricks), -1);

  OctreeNode root;
  root.brick_lo = {0, 0, 0};
  root.brick_hi = grid_;
  nodes_.push_back(root);
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    OctreeNode& n = nodes_[i];
    for (int a = 0; a < 3; ++a) {
      n.box.lo[a] = axis_lo(a, n.brick_lo[a]);
      n.box.hi[a] = axis_hi(a, n.brick_hi[a] - 1);
    }
    depth_ = std::max(depth_, n.level);
    if ((n.brick_hi[0] - n.brick_lo[0]) * (n.brick_hi[1] - n.brick_lo[1]) * (n.brick_hi[2] - n.brick_lo[2]) == 1) {
      n.brick = n.brick_lo[0] + grid_[0] * (n.brick_lo[1] + grid_[1] * n.brick_lo[2]);
      brick_node_[n.brick] = int(i);
      continue;
    }
    std::array<int, 3> mid;
    for (int a = 0; a < 3; ++a) {
      int len = n.brick_hi[a] - n.brick_lo[a];
      mid[a] = len > 1 ? n.brick_lo[a] + (len + 1) / 2 : -1;
    }
    for (int oct = 0; oct < 8; ++oct) {
      OctreeNode c;
      bool exists = true;
      for (int a = 0; a < 3; ++a) {
        bool upper = (oct >> a) & 1;
        if (mid[a] < 0) {
          if (upper) exists = false;
          c.brick_lo[a] = nodes_[i].brick_lo[a];
          c.brick_hi[a] = nodes_[i].brick_hi[a];
        } else {
          c.brick_lo[a] = upper ? mid[a] : nodes_[i].brick_lo[a];
          c.brick_hi[a] = upper ? nodes_[i].brick_hi[a] : mid[a];
        }
      }
      if (!exists) continue;
      c.level = nodes_[i].level + 1;
      c.parent = int(i);
      nodes_[i].children[oct] = int(nodes_.size());
      nodes_.push_back(c);  // may reallocate: nodes_[i] is re-indexed above, never held by reference
    }
  }
  node_level_brick_.assign(nodes_.size(), -1);
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    if (!nodes_[i].is_leaf()) {
      node_level_brick_[i] = brick_count() + int(level_nodes_.size());
      level_nodes_.push_back(int(i));
    }
}

int Octree::node_brick(int id) const {
  const OctreeNode& n = nodes_[std::size_t(id)];
  return n.brick >= 0 ? n.brick : node_level_brick_[std::size_t(id)];
}

std::array<int, 3> Octree::lod_factor(int id) const {
  const int f = 1 << lod_level(id);
  // Isotropic, except along an axis the whole grid is one brick thick (thin grids such as WRF's
  // 14 levels), which keeps its full resolution.
  return {grid_[0] > 1 ? f : 1, grid_[1] > 1 ? f : 1, grid_[2] > 1 ? f : 1};
}

int Octree::lod_level(int id) const {
  const OctreeNode& n = nodes_[std::size_t(id)];
  const int range = std::max({n.brick_hi[0] - n.brick_lo[0], n.brick_hi[1] - n.brick_lo[1],
                              n.brick_hi[2] - n.brick_lo[2]});
  int k = 0;
  while ((1 << k) < range) ++k;
  return k;
}

BrickLattice Octree::lattice(int i) const {
  BrickLattice l;
  if (i < brick_count()) {
    const Box s = brick_samples(i);
    for (int a = 0; a < 3; ++a) {
      l.origin[a] = s.lo[a];
      l.samples[a] = s.size(a);
    }
    return l;
  }
  const int id = level_nodes_[std::size_t(i - brick_count())];
  const OctreeNode& n = nodes_[std::size_t(id)];
  l.factor = lod_factor(id);
  for (int a = 0; a < 3; ++a) {
    // The node's samples run from box.lo to its shared upper layer (the grid's last sample for
    // the last node along the axis); cells/f ≤ S, so at most the leaf's S + 1 samples.
    const int cells = std::min(n.box.hi[a], dims_[a] - 1) - n.box.lo[a];
    l.origin[a] = n.box.lo[a];
    l.samples[a] = (cells + l.factor[a] - 1) / l.factor[a] + 1;
  }
  return l;
}

void Octree::stop_at(std::span<const std::uint8_t> flags) {
  if (flags.size() != nodes_.size())
    throw UsageError("octree stops: " + std::to_string(flags.size()) + " flags for " +
                     std::to_string(nodes_.size()) + " nodes");
  if (split_children_.empty()) {
    split_children_.resize(nodes_.size());
    for (std::size_t i = 0; i < nodes_.size(); ++i) split_children_[i] = nodes_[i].children;
  }
  stopped_.assign(nodes_.size(), 0);
  pruned_.assign(nodes_.size(), 0);
  bool any = false;
  // Parents come before their children in node order.
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    OctreeNode& n = nodes_[i];
    if (n.parent >= 0 && (pruned_[std::size_t(n.parent)] || stopped_[std::size_t(n.parent)]))
      pruned_[i] = 1;
    n.children = split_children_[i];
    if (node_level_brick_[i] < 0) continue;  // a finest leaf
    n.brick = -1;
    if (pruned_[i] || !flags[i]) continue;
    stopped_[i] = 1;
    any = true;
    n.brick = node_level_brick_[i];
    n.children = {-1, -1, -1, -1, -1, -1, -1, -1};
  }
  if (!any) {
    stopped_.clear();
    pruned_.clear();
  }
}

int Octree::stop_above(int id) const {
  if (stopped_.empty()) return -1;
  for (int i = id; i >= 0; i = nodes_[std::size_t(i)].parent)
    if (stopped_[std::size_t(i)]) return i;
  return -1;
}

int Octree::axis_lo(int a, int k) const { return k * cells_[a]; }

int Octree::axis_hi(int a, int k) const {
  return k == grid_[a] - 1 ? dims_[a] : (k + 1) * cells_[a];
}

std::array<int, 3> Octree::brick_coord(int b) const {
  return {b % grid_[0], (b / grid_[0]) % grid_[1], b / (grid_[0] * grid_[1])};
}

Box Octree::brick_box(int b) const {
  auto c = brick_coord(b);
  Box box;
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = axis_lo(a, c[a]);
    box.hi[a] = axis_hi(a, c[a]);
  }
  return box;
}

std::array<int, 3> Octree::max_brick_samples() const {
  Box s = brick_samples(0);
  return {s.size(0), s.size(1), s.size(2)};
}

Box Octree::brick_samples(int b) const {
  Box box = brick_box(b);
  for (int a = 0; a < 3; ++a) box.hi[a] = std::min(dims_[a], box.lo[a] + cells_[a] + 1);
  return box;
}

}  // namespace tsp

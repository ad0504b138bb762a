// The spatial skeleton of the TSP tree: a complete octree over the grid of leaf bricks.
//
// Bricks: along each axis the grid of D samples has D − 1 cells. That axis gets the fewest
// bricks n = ⌈(D − 1)/(B − 1)⌉ that keep each at most B samples, and the cells are spread
// evenly: every brick covers S = ⌈(D − 1)/n⌉ cells except the last, which covers the rest. A
// brick stores S + 1 samples (≤ B) and shares one sample layer with its upper neighbour. A brick's
// own voxel box (used for statistics, each voxel counted once) is [k·S, (k+1)·S), and the last
// brick along an axis also owns the final layer: [k·S, D).
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "tsp/core/types.h"

namespace tsp {

/// One octree node. Children are indexed by octant: bit 0 = upper x half, bit 1 = upper y,
/// bit 2 = upper z; −1 where the node is not split along that axis (thin grids).
struct OctreeNode {
  Box box;                       ///< own voxel box, half-open, without the overlap layer
  std::array<int, 3> brick_lo;   ///< brick-grid range covered, half-open
  std::array<int, 3> brick_hi;
  int level = 0;                 ///< root = 0
  int parent = -1;
  std::array<int, 8> children{-1, -1, -1, -1, -1, -1, -1, -1};
  int brick = -1;                ///< leaf brick index, −1 for internal nodes
  /// True for leaves (one brick).
  bool is_leaf() const { return brick >= 0; }
};

/// Where a stored brick's samples lie: sample j along axis a is at voxel coordinate
/// origin[a] + j·factor[a] (clamped to the grid's last sample). Leaf bricks have factor 1.
struct BrickLattice {
  std::array<int, 3> origin{};   ///< voxel coordinate of sample 0
  std::array<int, 3> factor{1, 1, 1};  ///< voxels between samples (a power of two)
  std::array<int, 3> samples{};  ///< stored samples per axis (≤ the stored brick shape)
  /// Number of samples.
  std::int64_t count() const { return std::int64_t(samples[0]) * samples[1] * samples[2]; }
};

/// Complete octree over the brick grid; nodes numbered breadth-first, root = 0. A node splits
/// each axis whose brick range is longer than 1 at lo + ⌈n/2⌉.
class Octree {
 public:
  /// Builds the octree for a dims grid with bricks of brick_size samples per axis.
  /// Throws UsageError when brick_size is not a power of two in [kMinBrickSize, kMaxBrickSize]
  /// or dims has a non-positive size.
  Octree(Dims dims, int brick_size);
  /// Grid size.
  Dims dims() const { return dims_; }
  /// B, brick edge in samples including the overlap layer.
  int brick_size() const { return brick_size_; }
  /// Number of octree nodes.
  int size() const { return int(nodes_.size()); }
  /// Node id.
  const OctreeNode& node(int id) const { return nodes_[id]; }
  /// Number of leaf bricks along each axis.
  std::array<int, 3> brick_grid() const { return grid_; }
  /// Number of leaf bricks.
  int brick_count() const { return grid_[0] * grid_[1] * grid_[2]; }
  /// Brick-grid coordinates of brick b (index = bx + nx·(by + ny·bz)).
  std::array<int, 3> brick_coord(int b) const;
  /// Own voxel box of brick b (half-open, no overlap).
  Box brick_box(int b) const;
  /// Stored sample box of brick b: the own box plus the upper neighbours' first layer.
  Box brick_samples(int b) const;
  /// Octree leaf node holding brick b.
  int brick_node(int b) const { return brick_node_[b]; }
  /// Largest node level (leaves of the deepest branch).
  int depth() const { return depth_; }
  /// Cells S each brick covers along axis a (the last brick may cover fewer).
  int brick_cells(int a) const { return cells_[a]; }
  /// Largest stored sample extent of any brick along each axis (brick 0's, ≤ B).
  std::array<int, 3> max_brick_samples() const;
  /// Calls f(b) for every leaf brick b below node id (its own brick for a leaf), in brick index
  /// order.
  template <class F>
  void for_each_brick(int id, F&& f) const {
    const OctreeNode& n = nodes_[std::size_t(id)];
    for (int z = n.brick_lo[2]; z < n.brick_hi[2]; ++z)
      for (int y = n.brick_lo[1]; y < n.brick_hi[1]; ++y)
        for (int x = n.brick_lo[0]; x < n.brick_hi[0]; ++x) f(x + grid_[0] * (y + grid_[1] * z));
  }

  // LOD levels (spec §14): every internal node also stores a brick of at most the leaf sample
  // count covering its region every lod_factor() voxels. Stored bricks are numbered leaves first
  // (0 … brick_count() − 1), then one level brick per internal node in node order.
  /// Leaf bricks plus level bricks.
  int stored_brick_count() const { return brick_count() + int(level_nodes_.size()); }
  /// Number of level bricks (internal nodes).
  int level_brick_count() const { return int(level_nodes_.size()); }
  /// The octree node stored brick i belongs to.
  int stored_brick_node(int i) const {
    return i < brick_count() ? brick_node_[i] : level_nodes_[i - brick_count()];
  }
  /// Stored brick of node id: its leaf brick, or its level brick for an internal node.
  int node_brick(int id) const;
  /// Voxels between node id's samples per axis: 2^lod_level(id), except 1 along an axis the
  /// whole grid is one brick thick (its full resolution is kept).
  std::array<int, 3> lod_factor(int id) const;
  /// LOD level of node id: log2 of the power of two at least its largest brick range (0 for the
  /// finest leaves; a stopped node keeps its level), so it grows strictly towards the root.
  int lod_level(int id) const;
  /// Largest lod_level (the root's).
  int max_lod_level() const { return lod_level(0); }
  /// Own voxel box of stored brick i (a leaf brick's, or its internal node's).
  Box stored_brick_box(int i) const {
    return i < brick_count() ? brick_box(i) : nodes_[std::size_t(stored_brick_node(i))].box;
  }
  /// Sample lattice of stored brick i.
  BrickLattice lattice(int i) const;

  // Adaptive octrees (Leven's, paper 000 §4.2; issue 31): the data ends at some internal nodes.
  /// Makes every flagged internal node (flags: one per node, 1 = stopped) a leaf whose brick is
  /// its level brick: its children become −1 and the nodes below it stay (ids, boxes, parents and
  /// brick_node() unchanged) but are unreachable from the root and hold no data. Flags on leaves
  /// and on nodes already below a stop are ignored. Throws UsageError when flags has not one
  /// entry per node.
  void stop_at(std::span<const std::uint8_t> flags);
  /// True when some node is stopped.
  bool has_stops() const { return !stopped_.empty(); }
  /// True for a node stop_at made a leaf.
  bool stopped(int id) const { return !stopped_.empty() && stopped_[std::size_t(id)] != 0; }
  /// False for a node below a stopped one (unreachable, no data of its own).
  bool reachable(int id) const { return pruned_.empty() || pruned_[std::size_t(id)] == 0; }
  /// True when stored brick i holds data: false for the leaf and level bricks of nodes below a
  /// stop (a reader makes up their samples from the stopped node's brick).
  bool brick_present(int i) const { return reachable(stored_brick_node(i)); }
  /// The stopped node above node id (itself when stopped), −1 when none.
  int stop_above(int id) const;
  /// Node id's children before stop_at (its children for a node never stopped).
  const std::array<int, 8>& split_children(int id) const {
    return stopped(id) ? split_children_[std::size_t(id)] : nodes_[std::size_t(id)].children;
  }

 private:
  Dims dims_;
  int brick_size_;
  std::array<int, 3> grid_;
  std::array<int, 3> cells_;
  int depth_ = 0;
  std::vector<OctreeNode> nodes_;
  std::vector<int> brick_node_;
  std::vector<int> level_nodes_;  // internal nodes in node order
  std::vector<int> node_level_brick_;  // per node: its level brick index, −1 for leaves
  std::vector<std::uint8_t> stopped_;  // per node, empty when no node is stopped
  std::vector<std::uint8_t> pruned_;   // per node: below a stopped node; empty when none
  std::vector<std::array<int, 8>> split_children_;  // per node: children before stop_at
  int axis_lo(int a, int k) const;
  int axis_hi(int a, int k) const;
};

}  // namespace tsp

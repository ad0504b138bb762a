// The incremental active-edge slicer (spec §7, paper §4.2 and Fig. 3): view-aligned slice
// polygons of one box at a time, in order, without a convex hull or a sort per polygon.
#pragma once
#include <array>

#include "tsp/frame/slicing.h"

namespace tsp {

/// Slices boxes by shared view-aligned planes. Once per view it computes each box edge's slope
/// (its intersection point's change per plane) and the order of corners at equal depth; per box
/// it sorts the 8 corners by depth, sweeps the planes back to front, updates an active edge list
/// at each corner it passes and reads each polygon off the active edges' current points.
/// slice() is const and keeps its state on the stack, so one slicer may serve several threads.
class IncrementalSlicer {
 public:
  /// Prepares the slopes for one view; throws UsageError when planes are invalid (validate()).
  explicit IncrementalSlicer(const SlicePlanes& planes);

  /// Appends the polygons of box to out: back to front (deepest plane first), each convex with 3
  /// to 6 vertices, counter-clockwise seen from the eye. Appends nothing for a box that is
  /// degenerate (not finite, or an extent within the tolerance of slice_rules.h) or that no plane
  /// cuts; throws UsageError when the spacing would give more than 2^24 slices through the box.
  void slice(const Aabb& box, PolygonSoup& out) const;

  /// The planes this slicer cuts with.
  const SlicePlanes& planes() const { return planes_; }

 private:
  SlicePlanes planes_;
  std::array<double, 3> inv_dir_{};  // 1/dir[a], 0 where dir[a] = 0
  std::array<double, 12> slope_{};   // per edge: change of its varying coordinate per plane
  std::array<int, 8> tie_key_{};     // corners of equal depth: smaller key first
};

}  // namespace tsp

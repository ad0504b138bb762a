// The splat cut (issue 14 item 4; TetSplat, paper 001): the last fallback when even the coarsest
// textured cut misses the frame budget. Every node of the cut is drawn as one splat — its mean
// colour and opacity over its box, composited exactly by the ray's length through it (the flat
// node's drawing) — and never textured. TetSplat's minimum splat size is the knob: a node is
// split only while its children would still project to at least min_px pixels across, so a
// larger minimum means fewer, larger splats and a faster frame.
#pragma once
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "tsp/frame/camera.h"
#include "tsp/lod/lod_error.h"
#include "tsp/tree/octree.h"
#include "tsp/tree/traversal.h"

namespace tsp {

/// One splat cut: LodStops with LodStop::splat on its nodes, and what it costs.
struct SplatCut {
  std::vector<LodStop> stops;  ///< one entry per octree node (LodStop::splat on the cut)
  int size = 0;                ///< nodes in the cut
  double pixel_area = 0;       ///< Σ of the cut nodes' screen rectangles (culled: 0)
  /// The minimum splat size it amounts to: half the largest projected extent among its nodes
  /// that could still split (0 when none can).
  double min_px = 0;
};

/// The projected extent of octree node id in pixels: the larger side of its screen rectangle.
/// Never throws.
double projected_extent(const Octree& octree, const Camera& camera, int id);

/// The splat cut for a minimum splat size of min_px pixels: from the root down, a node is split
/// when it has children and its projected extent is at least 2·min_px (its children then
/// project to about min_px or more); nodes clip marks removed (ClipSide::removed) are never split.
/// min_px ≤ 0: every leaf. Covers the volume exactly once. Never throws.
SplatCut splat_cut(const Octree& octree, const Camera& camera, double min_px, ClipSides clip = {});

/// The splat cut refined largest splat first within a screen-area budget: from the root, the
/// node with the largest projected extent that can split (it has children, is not removed by
/// clip) is split while the cut's Σ area after the split stays ≤ max_area and its node count ≤
/// max_nodes; the root alone when they allow nothing more. Covers the volume exactly once.
/// Never throws.
SplatCut splat_cut_within(const Octree& octree, const Camera& camera, double max_area,
                          ClipSides clip = {}, int max_nodes = std::numeric_limits<int>::max());
/// Same, from every node's projection (project_nodes; the LOD controller has them already).
SplatCut splat_cut_within(const Octree& octree, std::span<const NodeProjection> proj,
                          double max_area, ClipSides clip = {},
                          int max_nodes = std::numeric_limits<int>::max());

}  // namespace tsp

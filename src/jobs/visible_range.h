// --tf-range visible: the values the view shows — the extremes of one step over the leaf bricks
// inside the camera's view and not removed by the clip solid (ParaView's "rescale to visible
// range", from the tree's statistics: no voxel is read).
#pragma once
#include "tsp/clip/probe.h"
#include "tsp/core/types.h"
#include "tsp/frame/camera.h"
#include "tsp/tree/tsp_tree.h"

namespace tspgl {

/// The extreme values of step t over the leaf bricks of tree that camera sees (not wholly
/// outside its frustum) and clip keeps (clip may be inactive); tsp::step_value_range(tree, t)
/// when no leaf is seen. Asserts 0 <= t < steps. Never throws.
tsp::ValueRange visible_value_range(const tsp::TspTree& tree, int t, const tsp::Camera& camera,
                                    const tsp::ClipRegion& clip);

}  // namespace tspgl

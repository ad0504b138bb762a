// LaMar et al.'s selection filters (seed paper 002 §4.1): the cut chosen by a rule about where
// each tile lies relative to the viewer, not by its error. A depth-first walk from the root asks
// each node's filter for one of three answers — ignore it and its children (outside the view
// frustum), draw it (it satisfies the criterion), or look at its children — and the nodes drawn
// or ignored (and the leaves reached) form the cut:
//   distance: draw a tile when the distance from the viewpoint to its centre exceeds K times its
//             diagonal (the paper's K = 1): fine near the eye, coarser with distance;
//   fov:      draw a tile when it meets the view frustum and the angle it subtends at the eye
//             (its bounding sphere's) is less than half the field of view over K (K = 1 in the
//             paper); with an orthographic camera the angle is its screen rectangle's larger side
//             over the image height, and the field of view the whole image.
// Distances are in sample coordinates (voxels). `error` names today's error-driven cut (the
// LodController), which is not a selection filter.
#pragma once
#include <string>

#include "tsp/frame/camera.h"
#include "tsp/lod/lod_cut.h"
#include "tsp/tree/octree.h"

namespace tsp {

/// Which rule chooses the cut: the frame-time/error controller or one of LaMar's filters.
enum class LodFilter { error, distance, fov };

/// A filter and its factor K (> 0).
struct SelectionFilter {
  LodFilter kind = LodFilter::error;
  double scale = 1;  ///< K: larger refines more (distance: K × diagonal; fov: half-FOV / K)
  bool operator==(const SelectionFilter&) const = default;
};

/// "error", "distance" or "fov".
const char* to_string(LodFilter f);

/// Parses "error", "distance[:K]" or "fov[:K]" (K a finite number > 0). Throws UsageError naming
/// option and the text.
SelectionFilter parse_lod_filter(const std::string& text, const std::string& option);

/// A filter's answer for one node.
enum class Selection { ignore, draw, refine };

/// The filter's answer for octree node id under camera (a distance or fov filter; asserts it is
/// not LodFilter::error). Never throws.
Selection select_node(const Octree& octree, int id, const Camera& camera, const SelectionFilter& f);

/// The cut of LaMar's depth-first selection: from the root, a node that is ignored, drawn or a
/// leaf joins the cut, any other is replaced by its children. Covers the volume exactly once.
/// Asserts f is not LodFilter::error. Never throws.
LodCut selection_cut(const Octree& octree, const Camera& camera, const SelectionFilter& f);

}  // namespace tsp

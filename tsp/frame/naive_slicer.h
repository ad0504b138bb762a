// The naive slicer: each plane intersected with the box's 12 edges, the points sorted by angle.
// It is the incremental slicer's test oracle and benchmark baseline (spec §7).
#pragma once
#include "tsp/frame/slicing.h"

namespace tsp {

/// Appends the polygons of box to out with the same planes, order, orientation and degenerate
/// case rules as IncrementalSlicer::slice (back to front, counter-clockwise from the eye), by
/// intersecting every plane with all 12 edges, dropping duplicate points and sorting the rest by
/// angle around their centroid; throws UsageError when planes are invalid or give more than 2^24
/// slices through the box.
void naive_slice(const SlicePlanes& planes, const Aabb& box, PolygonSoup& out);

}  // namespace tsp

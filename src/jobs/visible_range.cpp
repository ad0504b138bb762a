#include "jobs/visible_range.h"

#include <algorithm>
#include <cassert>

#include "tsp/core/geometry.h"

namespace tspgl {

tsp::ValueRange visible_value_range(const tsp::TspTree& tree, int t, const tsp::Camera& camera,
                                    const tsp::ClipRegion& clip) {
  assert(t >= 0 && t < tree.time().steps());
  const tsp::Octree& octree = tree.octree();
  const int leaf_time = tree.time().leaf_of(t);
  float lo = 0, hi = 0;
  bool any = false;
  for (int o = 0; o < octree.size(); ++o) {
    const tsp::OctreeNode& n = octree.node(o);
    if (!n.is_leaf()) continue;
    const tsp::NodeStats& s = tree.stats(tree.id(o, leaf_time));
    if (s.empty()) continue;  // (outside a stencil's data)
    const tsp::Aabb box = tsp::geometric_box(n.box, octree.dims());
    if (clip.active() && clip.classify(box) == tsp::ClipSide::removed) continue;
    if (tsp::screen_footprint(camera, box).culled) continue;
    lo = any ? std::min(lo, s.min) : s.min;
    hi = any ? std::max(hi, s.max) : s.max;
    any = true;
  }
  if (!any || !(lo < hi)) return tsp::step_value_range(tree, t);
  return {lo, hi};
}

}  // namespace tspgl

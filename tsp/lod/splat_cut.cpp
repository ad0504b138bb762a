#include "tsp/lod/splat_cut.h"

#include <algorithm>

#include "tsp/lod/lod_error.h"

namespace tsp {

namespace detail {
// The larger side of a projection's screen rectangle (0 when culled).
double extent_of(const NodeProjection& p) {
  return p.culled ? 0 : std::max(p.rect[2] - p.rect[0], p.rect[3] - p.rect[1]);
}
}  // namespace detail

double projected_extent(const Octree& octree, const Camera& camera, int id) {
  return detail::extent_of(project_box(camera, geometric_box(octree.node(id).box, octree.dims())));
}

SplatCut splat_cut(const Octree& octree, const Camera& camera, double min_px, ClipSides clip) {
  SplatCut cut;
  cut.stops.assign(std::size_t(octree.size()), 0);
  // Depth first from the root: a node either stops (a splat) or passes on to its children.
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    const OctreeNode& n = octree.node(id);
    const NodeProjection p = project_box(camera, geometric_box(n.box, octree.dims()));
    const double extent = detail::extent_of(p);
    const bool removed = !clip.empty() && clip[std::size_t(id)] == 1;
    if (!n.is_leaf() && !removed && (min_px <= 0 || extent >= 2 * min_px)) {
      for (int c : n.children)
        if (c >= 0) stack.push_back(c);
      continue;
    }
    cut.stops[std::size_t(id)] = kSplatStop;
    ++cut.size;
    cut.pixel_area += p.culled || removed ? 0.0 : p.pixel_area;
  }
  return cut;
}

}  // namespace tsp

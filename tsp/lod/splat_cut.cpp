#include "tsp/lod/splat_cut.h"

#include <algorithm>
#include <queue>
#include <utility>

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
    if (!n.is_leaf() && !removed) cut.min_px = std::max(cut.min_px, 0.5 * extent);
  }
  return cut;
}

SplatCut splat_cut_within(const Octree& octree, const Camera& camera, double max_area,
                          ClipSides clip, int max_nodes) {
  const auto projection = [&](int id) {
    return project_box(camera, geometric_box(octree.node(id).box, octree.dims()));
  };
  const auto removed = [&](int id) { return !clip.empty() && clip[std::size_t(id)] == 1; };
  const auto area = [&](int id, const NodeProjection& p) {
    return p.culled || removed(id) ? 0.0 : p.pixel_area;
  };
  SplatCut cut;
  cut.stops.assign(std::size_t(octree.size()), 0);
  cut.stops[0] = kSplatStop;
  cut.size = 1;
  cut.pixel_area = area(0, projection(0));
  // Splittable cut nodes, largest extent first (ties: the smaller id, so the result is fixed).
  using Item = std::pair<double, int>;
  const auto later = [](const Item& a, const Item& b) {
    return a.first < b.first || (a.first == b.first && a.second > b.second);
  };
  std::priority_queue<Item, std::vector<Item>, decltype(later)> queue(later);
  const auto offer = [&](int id) {
    if (!octree.node(id).is_leaf() && !removed(id))
      queue.push({detail::extent_of(projection(id)), id});
  };
  offer(0);
  while (!queue.empty()) {
    const auto [extent, id] = queue.top();
    double after = cut.pixel_area - area(id, projection(id));
    int nodes = cut.size - 1;
    for (int c : octree.node(id).children)
      if (c >= 0) {
        after += area(c, projection(c));
        ++nodes;
      }
    if (after > max_area || nodes > max_nodes) break;
    queue.pop();
    cut.stops[std::size_t(id)] = 0;
    --cut.size;
    for (int c : octree.node(id).children)
      if (c >= 0) {
        cut.stops[std::size_t(c)] = kSplatStop;
        ++cut.size;
        offer(c);
      }
    cut.pixel_area = after;
  }
  cut.min_px = queue.empty() ? 0.0 : 0.5 * queue.top().first;
  return cut;
}

}  // namespace tsp

#include "tsp/lod/splat_cut.h"

#include <algorithm>
#include <queue>
#include <utility>

namespace tsp {

namespace detail {

// The larger side of a projection's screen rectangle (0 when culled).
double extent_of(const NodeProjection& p) {
  return p.culled ? 0 : std::max(p.rect[2] - p.rect[0], p.rect[3] - p.rect[1]);
}

// The one splat cut: from the root, the node with the largest projected extent that can split
// (it has children, is not removed by clip) is split while its extent is at least min_extent,
// the cut's Σ area after the split stays ≤ max_area and its node count ≤ max_nodes. A child's
// box lies inside its parent's, so it never projects larger: with only min_extent limiting, the
// cut splits exactly the nodes whose extent reaches it.
SplatCut greedy_cut(const Octree& octree, std::span<const NodeProjection> proj, double min_extent,
                    double max_area, int max_nodes, ClipSides clip) {
  const auto removed = [&](int id) { return !clip.empty() && clip[std::size_t(id)] == ClipSide::removed; };
  const auto area = [&](int id) {
    const NodeProjection& p = proj[std::size_t(id)];
    return p.culled || removed(id) ? 0.0 : p.pixel_area;
  };
  SplatCut cut;
  cut.stops.assign(std::size_t(octree.size()), LodStop::none);
  cut.stops[0] = LodStop::splat;
  cut.size = 1;
  cut.pixel_area = area(0);
  // Splittable cut nodes, largest extent first (ties: the smaller id, so the result is fixed).
  using Item = std::pair<double, int>;
  const auto later = [](const Item& a, const Item& b) {
    return a.first < b.first || (a.first == b.first && a.second > b.second);
  };
  std::priority_queue<Item, std::vector<Item>, decltype(later)> queue(later);
  const auto offer = [&](int id) {
    if (!octree.node(id).is_leaf() && !removed(id))
      queue.push({extent_of(proj[std::size_t(id)]), id});
  };
  offer(0);
  while (!queue.empty()) {
    const auto [extent, id] = queue.top();
    if (extent < min_extent) break;
    double after = cut.pixel_area - area(id);
    int nodes = cut.size - 1;
    for (int c : octree.node(id).children)
      if (c >= 0) {
        after += area(c);
        ++nodes;
      }
    if (after > max_area || nodes > max_nodes) break;
    queue.pop();
    cut.stops[std::size_t(id)] = LodStop::none;
    for (int c : octree.node(id).children)
      if (c >= 0) {
        cut.stops[std::size_t(c)] = LodStop::splat;
        offer(c);
      }
    cut.size = nodes;
    cut.pixel_area = after;
  }
  cut.min_px = queue.empty() ? 0.0 : 0.5 * queue.top().first;
  return cut;
}

}  // namespace detail

double projected_extent(const Octree& octree, const Camera& camera, int id) {
  return detail::extent_of(project_box(camera, geometric_box(octree.node(id).box, octree.dims())));
}

SplatCut splat_cut(const Octree& octree, const Camera& camera, double min_px, ClipSides clip) {
  return detail::greedy_cut(octree, project_nodes(octree, camera), min_px <= 0 ? 0 : 2 * min_px,
                            std::numeric_limits<double>::infinity(),
                            std::numeric_limits<int>::max(), clip);
}

SplatCut splat_cut_within(const Octree& octree, std::span<const NodeProjection> proj,
                          double max_area, ClipSides clip, int max_nodes) {
  return detail::greedy_cut(octree, proj, 0, max_area, max_nodes, clip);
}

SplatCut splat_cut_within(const Octree& octree, const Camera& camera, double max_area,
                          ClipSides clip, int max_nodes) {
  return splat_cut_within(octree, project_nodes(octree, camera), max_area, clip, max_nodes);
}

}  // namespace tsp

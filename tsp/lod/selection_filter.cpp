#include "tsp/lod/selection_filter.h"

#include <cassert>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/core/geometry.h"

namespace tsp {

namespace detail {

// The centre and the diagonal of node id's geometric box, in sample coordinates.
struct Tile {
  std::array<double, 3> centre{};
  double diagonal = 0;
  Aabb box;
};

Tile tile_of(const Octree& octree, int id) {
  Tile t;
  t.box = geometric_box(octree.node(id).box, octree.dims());
  t.centre = centre(t.box);
  t.diagonal = diagonal(t.box);
  return t;
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

constexpr double kPi = 3.14159265358979323846;

}  // namespace detail

const char* to_string(LodFilter f) {
  switch (f) {
    case LodFilter::distance:
      return "distance";
    case LodFilter::fov:
      return "fov";
    case LodFilter::error:
      break;
  }
  return "error";
}

SelectionFilter parse_lod_filter(const std::string& text, const std::string& option) {
  const auto bad = [&]() {
    return UsageError(option + " '" + text +
                      "': expected error, distance[:K] or fov[:K] with K a number > 0");
  };
  SelectionFilter f;
  const auto colon = text.find(':');
  const std::string name = text.substr(0, colon);
  if (name == "error" && colon == std::string::npos) return f;
  if (name == "distance")
    f.kind = LodFilter::distance;
  else if (name == "fov")
    f.kind = LodFilter::fov;
  else
    throw bad();
  if (colon != std::string::npos) {
    const std::string k = text.substr(colon + 1);
    char* end = nullptr;
    f.scale = std::strtod(k.c_str(), &end);
    if (k.empty() || end != k.c_str() + k.size() || !std::isfinite(f.scale) || !(f.scale > 0))
      throw bad();
  }
  return f;
}

Selection select_node(const Octree& octree, int id, const Camera& camera, const SelectionFilter& f) {
  assert(f.kind != LodFilter::error);
  const detail::Tile t = detail::tile_of(octree, id);
  if (f.kind == LodFilter::distance)
    return detail::distance(camera.eye(), t.centre) > f.scale * t.diagonal ? Selection::draw
                                                                           : Selection::refine;
  const ScreenFootprint s = screen_footprint(camera, t.box);
  if (s.culled) return Selection::ignore;
  if (camera.perspective()) {
    const double d = detail::distance(camera.eye(), t.centre), r = 0.5 * t.diagonal;
    const double beta = d > r ? 2 * std::asin(r / d) : detail::kPi;  // the eye inside: all around
    const double alpha = camera.params().fov_deg * detail::kPi / 180;
    return beta < 0.5 * alpha / f.scale ? Selection::draw : Selection::refine;
  }
  const double extent = std::max(s.rect[2] - s.rect[0], s.rect[3] - s.rect[1]);
  return extent < 0.5 * camera.params().height / f.scale ? Selection::draw : Selection::refine;
}

LodCut selection_cut(const Octree& octree, const Camera& camera, const SelectionFilter& f) {
  assert(f.kind != LodFilter::error);
  LodCut cut(octree);
  std::vector<int> todo{0};
  while (!todo.empty()) {
    const int id = todo.back();
    todo.pop_back();
    if (octree.node(id).is_leaf() || select_node(octree, id, camera, f) != Selection::refine)
      continue;
    cut.split(id);
    for (int c : octree.node(id).children)
      if (c >= 0) todo.push_back(c);
  }
  return cut;
}

}  // namespace tsp

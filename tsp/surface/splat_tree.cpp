#include "tsp/surface/splat_tree.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tsp {

namespace detail {

using V3 = std::array<double, 3>;

V3 sample_point(const Mesh& m, std::int64_t i, const V3& origin, const V3& spacing) {
  V3 p{};
  for (int a = 0; a < 3; ++a)
    p[std::size_t(a)] = (m.points[std::size_t(3 * i + a)] - origin[std::size_t(a)]) / spacing[std::size_t(a)];
  return p;
}

double dist(const std::array<float, 3>& a, const std::array<float, 3>& b) {
  return std::hypot(double(a[0]) - b[0], double(a[1]) - b[1], double(a[2]) - b[2]);
}

// The splat standing for nodes a and b.
SurfaceSplat merge(const SurfaceSplat& a, const SurfaceSplat& b) {
  SurfaceSplat s;
  s.area = a.area + b.area;
  const double wa = s.area > 0 ? a.area / s.area : 0.5, wb = 1 - wa;
  double n2 = 0;
  std::array<double, 3> n{};
  for (std::size_t k = 0; k < 3; ++k) {
    s.centre[k] = float(wa * a.centre[k] + wb * b.centre[k]);
    n[k] = wa * a.normal[k] + wb * b.normal[k];
    n2 += n[k] * n[k];
  }
  if (n2 > 0)
    for (std::size_t k = 0; k < 3; ++k) s.normal[k] = float(n[k] / std::sqrt(n2));
  else
    s.normal = a.normal;  // opposite halves (a thin plate): either side
  s.value = float(wa * a.value + wb * b.value);
  s.radius = float(std::max(dist(s.centre, a.centre) + a.radius, dist(s.centre, b.centre) + b.radius));
  return s;
}

// A leaf: its splat and its triangle.
struct Leaf {
  SurfaceSplat splat;
  std::array<std::array<float, 3>, 3> triangle;
};

// Builds the subtree over leaves[b, e) in pre-order into tree; returns its root's id.
int build(std::vector<Leaf>& leaves, std::size_t b, std::size_t e, SplatTree& tree) {
  const int id = int(tree.nodes.size());
  tree.nodes.emplace_back();
  if (e - b == 1) {
    tree.nodes[std::size_t(id)].splat = leaves[b].splat;
    tree.nodes[std::size_t(id)].triangle = leaves[b].triangle;
    return id;
  }
  std::array<float, 3> lo = leaves[b].splat.centre, hi = lo;
  for (std::size_t i = b; i < e; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], leaves[i].splat.centre[k]);
      hi[k] = std::max(hi[k], leaves[i].splat.centre[k]);
    }
  std::size_t axis = 0;
  for (std::size_t k = 1; k < 3; ++k)
    if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
  const std::size_t mid = b + (e - b) / 2;
  std::nth_element(leaves.begin() + std::ptrdiff_t(b), leaves.begin() + std::ptrdiff_t(mid),
                   leaves.begin() + std::ptrdiff_t(e),
                   [axis](const Leaf& x, const Leaf& y) { return x.splat.centre[axis] < y.splat.centre[axis]; });
  const int c0 = build(leaves, b, mid, tree);
  const int c1 = build(leaves, mid, e, tree);
  SplatTreeNode& n = tree.nodes[std::size_t(id)];
  n.child = {c0, c1};
  n.splat = merge(tree.nodes[std::size_t(c0)].splat, tree.nodes[std::size_t(c1)].splat);
  return id;
}

}  // namespace detail

SplatTree build_splat_tree(const Mesh& mesh, const BoundaryTriangles& boundary,
                           const std::array<double, 3>& origin,
                           const std::array<double, 3>& spacing) {
  using detail::V3;
  std::vector<detail::Leaf> leaves;
  leaves.reserve(boundary.points.size());
  SplatTree tree;
  tree.value_range = {0, 0};
  bool first = true;
  for (std::size_t t = 0; t < boundary.points.size(); ++t) {
    const auto& ids = boundary.points[t];
    const V3 p0 = detail::sample_point(mesh, ids[0], origin, spacing),
             p1 = detail::sample_point(mesh, ids[1], origin, spacing),
             p2 = detail::sample_point(mesh, ids[2], origin, spacing);
    const V3 u{p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, v{p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    const V3 n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = std::hypot(n[0], n[1], n[2]);
    if (!(len > 0)) continue;  // degenerate (or not finite)
    SurfaceSplat s;
    double r2 = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      s.centre[k] = float((p0[k] + p1[k] + p2[k]) / 3);
      s.normal[k] = float(n[k] / len);
    }
    for (const V3* p : {&p0, &p1, &p2}) {
      double d2 = 0;
      for (std::size_t k = 0; k < 3; ++k) d2 += ((*p)[k] - s.centre[k]) * ((*p)[k] - s.centre[k]);
      r2 = std::max(r2, d2);
    }
    s.radius = float(std::sqrt(r2));
    s.area = float(0.5 * len);
    if (mesh.cell_values)
      s.value = mesh.values[std::size_t(boundary.cell[t])];
    else
      s.value = (mesh.values[std::size_t(ids[0])] + mesh.values[std::size_t(ids[1])] +
                 mesh.values[std::size_t(ids[2])]) / 3.f;
    if (first || s.value < tree.value_range.lo) tree.value_range.lo = s.value;
    if (first || s.value > tree.value_range.hi) tree.value_range.hi = s.value;
    first = false;
    detail::Leaf leaf{s, {}};
    for (std::size_t k = 0; k < 3; ++k) {
      leaf.triangle[0][k] = float(p0[k]);
      leaf.triangle[1][k] = float(p1[k]);
      leaf.triangle[2][k] = float(p2[k]);
    }
    leaves.push_back(leaf);
  }
  tree.leaves = int(leaves.size());
  if (leaves.empty()) return tree;
  tree.nodes.reserve(2 * leaves.size() - 1);
  detail::build(leaves, 0, leaves.size(), tree);
  return tree;
}

double projected_diameter(const Camera& camera, const SurfaceSplat& s) {
  const glm::dmat4& view = camera.view();
  const glm::dvec4 e = view * glm::dvec4(s.centre[0], s.centre[1], s.centre[2], 1.0);
  // The view's largest stretch of a sample unit (1 for cubic voxels).
  const double stretch = std::max({glm::length(glm::dvec3(view[0])), glm::length(glm::dvec3(view[1])),
                                   glm::length(glm::dvec3(view[2]))});
  const double px_per_unit = camera.projection()[0][0] * 0.5 * camera.params().width;
  double d = 2.0 * s.radius * stretch * px_per_unit;
  if (camera.perspective()) {
    if (e.z >= 0) return 0;  // behind the eye
    d /= -e.z;
  }
  return d;
}

std::vector<int> splat_surface_cut(const SplatTree& tree, const Camera& camera, double min_px) {
  std::vector<int> cut;
  if (tree.nodes.empty()) return cut;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    const SplatTreeNode& n = tree.nodes[std::size_t(id)];
    if (n.is_leaf() || (min_px > 0 && projected_diameter(camera, n.splat) <= min_px)) {
      cut.push_back(id);
      continue;
    }
    stack.push_back(n.child[1]);
    stack.push_back(n.child[0]);
  }
  return cut;
}

}  // namespace tsp

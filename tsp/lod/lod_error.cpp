#include "tsp/lod/lod_error.h"

#include <algorithm>
#include <cmath>

namespace tsp {

TfColourSlopes::TfColourSlopes(const TransferFunction& tf) : tf_(&tf) {
  const int k = tf.size();
  std::vector<Luv> luv(static_cast<std::size_t>(k));
  for (int j = 0; j < k; ++j) {
    const Rgba& c = tf.entry(j);
    luv[std::size_t(j)] = srgb_to_luv(c.r * c.a, c.g * c.a, c.b * c.a);
  }
  const double width = tf.domain().width() / k;
  step_.resize(std::size_t(std::max(0, k - 1)));
  for (int j = 0; j + 1 < k; ++j)
    step_[std::size_t(j)] =
        delta_e_luv(luv[std::size_t(j)], luv[std::size_t(j) + 1]) / std::max(width, 1e-300);
}

double TfColourSlopes::slope(double lo, double hi) const {
  const int a = std::max(0, tf_->entry_of(lo) - 1);
  const int b = std::min(tf_->size() - 1, tf_->entry_of(hi) + 1);
  if (tf_->transparent(a, b)) return 0;
  double s = 0;
  for (int j = a; j < b; ++j) s = std::max(s, step_[std::size_t(j)]);
  return s;
}

bool TfColourSlopes::transparent(double lo, double hi) const {
  return tf_->transparent(tf_->entry_of(lo), tf_->entry_of(hi));
}

std::vector<NodeProjection> project_nodes(const Octree& octree, const Camera& camera) {
  std::vector<NodeProjection> proj(std::size_t(octree.size()));
  for (int id = 0; id < octree.size(); ++id)
    proj[std::size_t(id)] = project_box(camera, geometric_box(octree.node(id).box, octree.dims()));
  return proj;
}

NodeProjection project_box(const Camera& camera, const Aabb& box) {
  NodeProjection p;
  const glm::dmat4 vp = camera.view_projection();
  const double w = camera.params().width, h = camera.params().height;
  const ScreenFootprint fp = screen_footprint(camera, box);
  p.culled = fp.culled;
  const auto [x0, y0, x1, y1] = fp.rect;
  p.rect = {std::clamp(x0, 0.0, w), std::clamp(y0, 0.0, h), std::clamp(x1, 0.0, w),
            std::clamp(y1, 0.0, h)};
  p.pixel_area = std::max(0.0, p.rect[2] - p.rect[0]) * std::max(0.0, p.rect[3] - p.rect[1]);
  const auto dir = camera.direction();
  for (int a = 0; a < 3; ++a) p.depth_voxels += std::fabs((box.hi[a] - box.lo[a]) * dir[a]);
  // Pixels per voxel: one voxel along the camera's right vector at the point nearest the eye.
  const glm::dmat4& view = camera.view();
  const glm::dvec3 right(view[0][0], view[1][0], view[2][0]);
  glm::dvec3 q;
  const auto eye = camera.eye();
  for (int a = 0; a < 3; ++a)
    q[a] = camera.perspective() ? std::clamp(eye[a], box.lo[a], box.hi[a])
                                : 0.5 * (box.lo[a] + box.hi[a]);
  if (camera.perspective()) {  // at least a little in front of the eye
    const glm::dvec3 d(dir[0], dir[1], dir[2]);
    const double ahead = glm::dot(q - glm::dvec3(eye[0], eye[1], eye[2]), d);
    if (ahead < 1.0) q += d * (1.0 - ahead);
  }
  const glm::dvec4 a = vp * glm::dvec4(q, 1.0), b = vp * glm::dvec4(q + right, 1.0);
  if (a.w > 1e-9 && b.w > 1e-9)
    p.pixels_per_voxel = std::hypot((b.x / b.w - a.x / a.w) * 0.5 * w, (b.y / b.w - a.y / a.w) * 0.5 * h);
  return p;
}

std::vector<double> leaf_visibility(const TspTree& tree, int t, const Camera& camera,
                                    const std::vector<NodeProjection>& leaves,
                                    const TransferFunction& tf) {
  constexpr int kTiles = 32;  // per axis
  const Octree& o = tree.octree();
  const double w = camera.params().width, h = camera.params().height;
  const auto dir = camera.direction();
  const auto eye = camera.eye();
  // Leaves front to back: by depth along the view (orthographic) or distance from the eye.
  std::vector<std::pair<double, int>> order;
  for (int b = 0; b < o.brick_count(); ++b) {
    const Box& box = o.brick_box(b);
    double key = 0;
    for (int a = 0; a < 3; ++a) {
      const double c = 0.5 * (box.lo[a] + box.hi[a]);
      key += camera.perspective() ? (c - eye[a]) * (c - eye[a]) : c * dir[a];
    }
    order.push_back({key, b});
  }
  std::sort(order.begin(), order.end());
  std::vector<double> transmittance(std::size_t(kTiles) * kTiles, 1.0), vis(order.size(), 0.0);
  for (const auto& [key, b] : order) {
    const NodeProjection& p = leaves[std::size_t(b)];
    if (p.culled || p.pixel_area <= 0) continue;
    const int x0 = std::clamp(int(p.rect[0] / w * kTiles), 0, kTiles - 1);
    const int x1 = std::clamp(int(p.rect[2] / w * kTiles), 0, kTiles - 1);
    const int y0 = std::clamp(int(p.rect[1] / h * kTiles), 0, kTiles - 1);
    const int y1 = std::clamp(int(p.rect[3] / h * kTiles), 0, kTiles - 1);
    double sum = 0;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) sum += transmittance[std::size_t(y) * kTiles + x];
    vis[std::size_t(b)] = sum / double((x1 - x0 + 1) * (y1 - y0 + 1));
    // α per voxel (spec §9) over the leaf's mean chord: voxels / area.
    const NodeStats& s = tree.stats(tree.id(o.brick_node(b), tree.time().leaf_of(t)));
    // The TF's mean α over the leaf's typical values, mean ± one standard deviation.
    const int j0 = tf.entry_of(s.mean - s.std), j1 = tf.entry_of(s.mean + s.std);
    double a = 0;
    for (int j = j0; j <= j1; ++j) a += tf.entry(j).a;
    a = std::clamp(a / double(j1 - j0 + 1), 0.0, 1.0);
    const double area_voxels = p.pixel_area / std::max(p.pixels_per_voxel * p.pixels_per_voxel, 1e-12);
    const double chord = std::min(p.depth_voxels, double(o.brick_box(b).count()) / area_voxels);
    const double keep = std::pow(1 - a, chord);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) transmittance[std::size_t(y) * kTiles + x] *= keep;
  }
  return vis;
}

double view_weight(const NodeProjection& p, const Camera& camera) {
  const double w = camera.params().width, h = camera.params().height;
  const double cx = 0.5 * (p.rect[0] + p.rect[2]) - 0.5 * w, cy = 0.5 * (p.rect[1] + p.rect[3]) - 0.5 * h;
  return 1.0 / (1.0 + std::hypot(cx, cy) / std::max(0.5 * std::hypot(w, h), 1e-9));
}

double focus_weight(const std::array<double, 3>& c, const std::array<double, 3>& focus,
                    double diagonal) {
  const double d = std::hypot(c[0] - focus[0], c[1] - focus[1], c[2] - focus[2]);
  return 1.0 / (1.0 + 2.0 * d / std::max(diagonal, 1e-9));
}

double lod_error(const TspTree& tree, int o, int t, const NodeProjection& p,
                 const TfColourSlopes& slopes, double weight) {
  const Octree& octree = tree.octree();
  if (p.culled || octree.node(o).is_leaf()) return 0;
  const NodeStats& s = tree.stats(tree.id(o, tree.time().leaf_of(t)));
  if (s.empty()) return 0;
  const double colour = double(tree.level_error(o, t)) * slopes.slope(s.min, s.max);
  const auto f = octree.lod_factor(o);
  const double texel = double(std::max({f[0], f[1], f[2]})) * p.pixels_per_voxel;
  return texel * colour * weight;
}

}  // namespace tsp

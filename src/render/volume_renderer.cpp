#include "render/volume_renderer.h"

#include "tsp/core/stopwatch.h"
#include "tsp/frame/frame_plan.h"
#include "tsp/frame/slicer.h"
#include "tsp/tree/traversal.h"

namespace tspgl {

namespace {

tsp::ViewOrder view_order(const tsp::Camera& camera) {
  return camera.perspective() ? tsp::ViewOrder::perspective(camera.eye())
                              : tsp::ViewOrder::orthographic(camera.direction());
}

}  // namespace

VolumeRenderer::VolumeRenderer(GlContext& ctx, const tsp::BrickStore& bricks,
                               tsp::CachePolicy cache, std::int64_t texture_budget,
                               std::int64_t brick_budget)
    : tree_(bricks.tree()),
      cache_(texture_budget, cache),
      bricks_(bricks, brick_budget),
      compositor_(ctx),
      textures_(ctx.gl(), bricks_) {}

VolumeRenderer::~VolumeRenderer() = default;

void VolumeRenderer::set_transfer_function(const tsp::TransferFunction& tf) {
  compositor_.set_transfer_function(tf, tree_.value_range());
}

void VolumeRenderer::clear_textures() {
  textures_.clear();
  cache_.clear();
}

int VolumeRenderer::drop_unreachable(tsp::FrameMetric& metric, const tsp::Tolerances& tol) {
  const auto dropped = cache_.drop_unreachable(tsp::reachable_textures(tree_, metric, tol));
  for (const tsp::TextureKey& k : dropped) textures_.erase(k);
  return int(dropped.size());
}

std::vector<tsp::BrickKey> VolumeRenderer::bricks_to_upload(int step, const tsp::Camera& camera,
                                                            const RenderSettings& settings,
                                                            tsp::FrameMetric& metric) const {
  const tsp::ViewOrder order = view_order(camera);
  const tsp::NodeErrors& errors = metric.errors_for_step(step);
  std::vector<tsp::BrickKey> keys;
  for (const tsp::Emitted& e : tsp::traverse(tree_, step, settings.tol, errors, order)) {
    const int id = tree_.id(e.octree_id, e.time_id);
    if (tsp::shading_of(metric.class_info(id), settings.tol) != tsp::Shading::textured) continue;
    for (int brick : tsp::leaf_bricks(tree_.octree(), e.octree_id, order))
      if (!textures_.contains(tsp::TextureKey{brick, e.span.t0, 0}))
        keys.push_back({brick, e.span.t0});
  }
  return keys;
}

FrameReport VolumeRenderer::render(int step, const tsp::Camera& camera,
                                   const RenderSettings& settings, tsp::FrameMetric& metric) {
  const tsp::Stopwatch frame;
  const tsp::Octree& octree = tree_.octree();
  FrameReport r;
  r.step = step;
  compositor_.begin_frame(camera, settings);

  tsp::Stopwatch phase;
  const tsp::ViewOrder order = view_order(camera);
  // errors_for_step makes every node this step's traversal can reach current, so class_info and
  // mean_colour below only read memoised results.
  const tsp::NodeErrors& errors = metric.errors_for_step(step);
  const std::vector<tsp::Emitted> emitted = tsp::traverse(tree_, step, settings.tol, errors, order);
  const tsp::FramePlan plan = tsp::plan_frame(tree_, step, emitted, tsp::node_info(metric),
                                              settings.tol, order, cache_, settings.upload_budget);
  r.traversal_ms = phase.lap_ms();

  const tsp::IncrementalSlicer slicer(tsp::SlicePlanes::toward(camera.direction(), settings.spacing));
  soup_.clear();
  std::vector<DrawItem> items;
  std::vector<std::size_t> textured_items;  // item index per planned texture drawn textured
  textured_items.reserve(plan.textures.size());
  auto add = [&](const tsp::Aabb& box) -> DrawItem& {
    DrawItem& it = items.emplace_back();
    it.first_polygon = int(soup_.size());
    slicer.slice(box, soup_);
    it.polygon_count = int(soup_.size()) - it.first_polygon;
    return it;
  };
  for (const tsp::PlannedNode& n : plan.nodes) {
    if (n.cls == tsp::DrawClass::not_rendered) continue;
    const int tsp_id = tree_.id(n.node.octree_id, n.node.time_id);
    if (n.cls == tsp::DrawClass::untextured) {
      add(tsp::geometric_box(octree.node(n.node.octree_id).box, octree.dims())).colour =
          flat_colour(metric.mean_colour(tsp_id), settings.spacing);
      continue;
    }
    for (int i = n.first_texture; i < n.first_texture + n.texture_count; ++i) {
      const tsp::PlannedTexture& pt = plan.textures[std::size_t(i)];
      const int brick = pt.key.brick;
      DrawItem& it = add(tsp::geometric_box(octree.brick_box(brick), octree.dims()));
      if (pt.deferred) {  // not uploaded yet: the node's mean colour meanwhile
        it.colour = flat_colour(metric.mean_colour(tsp_id), settings.spacing);
        continue;
      }
      it.samples = octree.brick_samples(brick);
      textured_items.push_back(items.size() - 1);
    }
  }
  compositor_.upload(soup_);
  r.slicing_ms = phase.lap_ms();
  r.polygons = std::int64_t(soup_.size());

  for (const tsp::TextureKey& k : plan.evict_before) textures_.erase(k);
  std::size_t next_item = 0;
  for (const tsp::PlannedTexture& pt : plan.textures) {
    if (pt.deferred) continue;
    items[textured_items[next_item++]].texture =
        pt.upload ? textures_.upload(pt.key) : textures_.at(pt.key);
  }
  r.upload_ms = phase.lap_ms();

  compositor_.draw(items);
  for (const tsp::TextureKey& k : plan.release_after) textures_.erase(k);
  compositor_.end_frame();
  r.draw_ms = phase.lap_ms();
  r.ms = frame.ms();

  for (int c = 0; c < tsp::kDrawClassCount; ++c)
    r.class_percent[std::size_t(c)] = plan.percent(tsp::DrawClass(c));
  r.bytes_uploaded = plan.bytes_uploaded;
  r.textures_resident = plan.textures_resident;
  r.texture_bytes = plan.texture_bytes;
  r.deferred_textures = plan.deferred;
  return r;
}

}  // namespace tspgl

#include "render/volume_renderer.h"

#include <algorithm>

#include "render/texture_samples.h"
#include "tsp/core/stopwatch.h"
#include "tsp/frame/frame_plan.h"
#include "tsp/frame/slicer.h"
#include "tsp/metric/level_tf.h"
#include "tsp/tree/traversal.h"

namespace tspgl {

namespace {

// Values of tsp::Shading, for page tags.
constexpr int kShadingCount = 3;

// The traversal's transparency for our rule (RenderSettings::skip_transparent), read from the
// metric's classes; empty: the paper's rule.
tsp::TransparentFn transparency(const RenderSettings& s, tsp::FrameMetric& metric) {
  if (!s.skip_transparent) return {};
  return [&metric](int id) { return metric.class_info(id).transparent; };
}

tsp::ViewOrder view_order(const tsp::Camera& camera) {
  return camera.perspective() ? tsp::ViewOrder::perspective(camera.eye())
                              : tsp::ViewOrder::orthographic(camera.direction());
}

// The plan's full-resolution textures that are drawn (uploaded) this frame.
std::vector<tsp::TextureKey> level0_keys(const tsp::FramePlan& plan) {
  std::vector<tsp::TextureKey> level0;
  for (const tsp::PlannedTexture& pt : plan.textures)
    if (!pt.deferred && pt.key.level == 0) level0.push_back(pt.key);
  return level0;
}

}  // namespace

VolumeRenderer::VolumeRenderer(GlContext& ctx, const tsp::BrickStore& bricks,
                               tsp::CachePolicy cache, std::int64_t texture_budget,
                               std::int64_t brick_budget,
                               std::shared_ptr<SliceCompositor> compositor)
    : tree_(bricks.tree()),
      // The cache counts 16-bit samples; a stencilled texel holds two (RG16).
      cache_(tree_.has_stencil() ? texture_budget / 2 : texture_budget, cache),
      bricks_(bricks, brick_budget),
      compositor_(compositor ? std::move(compositor) : std::make_shared<SliceCompositor>(ctx)),
      textures_(ctx.gl(), bricks_),
      dense_(ctx.gl(), bricks_) {
  compositor_->set_stencil(tree_.has_stencil());
  histogram_.assign(bricks.histogram().begin(), bricks.histogram().end());
}

VolumeRenderer::~VolumeRenderer() = default;

void VolumeRenderer::set_transfer_function(const tsp::TransferFunction& tf) {
  // The coarse levels' blur weighs values by how many samples take them (the file's histogram).
  compositor_->set_transfer_function(tf, tree_.value_range(),
                                     tsp::entry_prior(tf, histogram_, tree_.value_range()));
  tf_ = tf;
  variation_.reset();
  textures_.forget_variations();
  ++tf_serial_;
}

void VolumeRenderer::set_clip(const tsp::ClipRegion& clip,
                              const std::optional<tsp::TransferFunction>& surface) {
  const bool same = clip == clip_ && !surface && !clip_surface_;
  clip_ = clip;
  clip_surface_ = clip.active() && surface.has_value();
  // One voxel of margin: the surface crosses textured bricks only (render/dense_volume.h).
  clip_sides_ = clip_.classify_nodes(tree_.octree(), 1.0);
  // A solid that keeps the whole volume (its root kept, with the margin) clips nothing: the
  // plain caster, without the clip code's cost.
  if (!clip_sides_.empty() && clip_sides_[0] == tsp::ClipSide::kept) {
    clip_sides_.clear();
    clip_surface_ = false;
  }
  compositor_->set_clip(clip_sides_.empty() ? tsp::ClipRegion{} : clip_,
                        clip_surface_ ? &*surface : nullptr, tree_.value_range());
  if (!same) ++clip_serial_;
}

VolumeRenderer::ReuseKey VolumeRenderer::reuse_key(const tsp::Camera& camera,
                                                   const RenderSettings& s) const {
  ReuseKey k;
  k.view_projection = camera.view_projection();
  k.width = camera.params().width;
  k.height = camera.params().height;
  k.spacing = s.spacing;
  k.compositing = s.compositing;
  k.exact_flat = s.exact_flat;
  k.preintegrated = s.preintegrated;
  k.shade = s.shade;
  k.level_tf = s.level_tf;
  k.skip_transparent = s.skip_transparent;
  k.background = s.background;
  k.tf_serial = tf_serial_;
  k.clip_serial = clip_serial_;
  k.render_scale = s.render_scale;
  k.sampling_tol = s.sampling_tol;
  k.refine_tol = s.refine_tol;
  k.backend = s.backend;  // the casters' pictures differ in the last bit: never mixed
  k.surface = s.surface && compositor_->has_surface();  // a frame with it is never kept, nor one after
  return k;
}

tsp::TraversalQuery VolumeRenderer::traversal(int step, const RenderSettings& s,
                                              tsp::FrameMetric& metric,
                                              const tsp::NodeErrors& errors,
                                              const tsp::ViewOrder& order,
                                              tsp::LodStops stops) const {
  return {.tree = tree_,
          .step = step,
          .tol = s.tol,
          .errors = errors,
          .view = order,
          .stops = stops,
          .clip = clip_sides_,
          .transparent = transparency(s, metric)};
}

void VolumeRenderer::clear_textures() {
  previous_.reset();
  textures_.clear();
  dense_.clear();
  cache_.clear();
}

int VolumeRenderer::drop_unreachable(tsp::FrameMetric& metric, const tsp::Tolerances& tol,
                                     bool skip_transparent, tsp::SpanStep span_step,
                                     tsp::LodStops stops) {
  const auto dropped = cache_.drop_unreachable(
      tsp::reachable_textures(tree_, metric, tol, skip_transparent, span_step, stops));
  for (const tsp::TextureKey& k : dropped) textures_.erase(k);
  return int(dropped.size());
}

std::vector<tsp::BrickKey> VolumeRenderer::bricks_to_upload(int step, const tsp::Camera& camera,
                                                            const RenderSettings& settings,
                                                            tsp::FrameMetric& metric,
                                                            tsp::LodStops stops) const {
  std::vector<tsp::BrickKey> keys;
  for (const tsp::TextureKey& k : textures_to_upload(step, camera, settings, metric, stops))
    for (int t = k.t0; t <= k.last_step(); ++t) keys.push_back({k.brick, t});
  return keys;
}

std::vector<tsp::TextureKey> VolumeRenderer::textures_to_upload(int step,
                                                                const tsp::Camera& camera,
                                                                const RenderSettings& settings,
                                                                tsp::FrameMetric& metric,
                                                                tsp::LodStops stops) const {
  const tsp::ViewOrder order = view_order(camera);
  const tsp::NodeErrors& errors = metric.errors_for_step(step);
  std::vector<tsp::TextureKey> keys;
  for (const tsp::Emitted& e :
       tsp::traverse(traversal(step, settings, metric, errors, order, stops))) {
    const int id = tree_.id(e.octree_id, e.time_id);
    // Clipped away, skipped, flat or a splat: no brick.
    if (tsp::emitted_shading(tree_, e, metric.class_info(id), settings.tol, stops, clip_surface_) !=
        tsp::Shading::textured)
      continue;
    for (int brick : tsp::node_bricks(tree_.octree(), e.octree_id, order, stops)) {
      const tsp::TextureKey k =
          tsp::span_texture_key(tree_.octree(), brick, e.span, settings.span_step);
      if (!textures_.contains(k)) keys.push_back(k);
    }
  }
  return keys;
}

void VolumeRenderer::fill_items(const tsp::FramePlan& plan, tsp::FrameMetric& metric,
                                const tsp::Camera& camera, const RenderSettings& settings) {
  const tsp::Octree& octree = tree_.octree();
  const tsp::IncrementalSlicer slicer(tsp::SlicePlanes::toward(camera.direction(), settings.spacing * camera.ray_cosine()));
  soup_.clear();
  items_.clear();
  auto add = [&](const tsp::Aabb& box, bool as_box) -> DrawItem& {
    DrawItem& it = items_.emplace_back();
    it.as_box = as_box;
    it.bounds = box;
    if (as_box) return it;
    it.first_polygon = int(soup_.size());
    slicer.slice(box, soup_);
    it.polygon_count = int(soup_.size()) - it.first_polygon;
    return it;
  };
  auto add_flat = [&](const tsp::Aabb& box, int tsp_id) {
    const tsp::Rgba c = metric.mean_colour(tsp_id);
    DrawItem& it = add(box, settings.exact_flat);
    it.flat = c;
    it.colour = flat_colour(c, settings.spacing);
  };
  for (const tsp::PlannedNode& n : plan.nodes) {
    if (n.cls == tsp::DrawClass::not_rendered) continue;
    const int tsp_id = tree_.id(n.node.octree_id, n.node.time_id);
    if (n.cls == tsp::DrawClass::untextured) {
      add_flat(tsp::geometric_box(octree.node(n.node.octree_id).box, octree.dims()), tsp_id);
      continue;
    }
    for (int i = n.first_texture; i < n.first_texture + n.texture_count; ++i) {
      const tsp::PlannedTexture& pt = plan.textures[std::size_t(i)];
      const tsp::Aabb box =
          tsp::geometric_box(octree.stored_brick_box(pt.key.brick), octree.dims());
      if (pt.deferred) {  // not uploaded yet: the node's mean colour meanwhile
        add_flat(box, tsp_id);
        continue;
      }
      add(box, settings.compositing == Compositing::boxes).slot = textures_.at(pt.key);
    }
  }
  compositor_->upload(soup_);
}

bool VolumeRenderer::dense_frame(const tsp::FramePlan& plan) {
  const tsp::Octree& octree = tree_.octree();
  dense_keys_.assign(std::size_t(octree.brick_count()), tsp::TextureKey{});
  int covered = 0;
  for (const tsp::PlannedNode& n : plan.nodes) {
    if (n.cls == tsp::DrawClass::not_rendered) continue;
    if (n.cls == tsp::DrawClass::untextured) return false;  // flat: the grid walk draws it exactly
    if (n.cls == tsp::DrawClass::clipped) {
      // Clipped away: the caster's kept intervals jump over it, so its texels are never
      // sampled and need no update (brick −1).
      octree.for_each_brick(n.node.octree_id, [&](int) { ++covered; });
      continue;
    }
    for (int i = n.first_texture; i < n.first_texture + n.texture_count; ++i) {
      const tsp::PlannedTexture& pt = plan.textures[std::size_t(i)];
      if (pt.deferred || pt.key.level != 0) return false;  // a mean colour, or a level brick
      // (Neighbours from different steps — a temporal tolerance merged one's span — share one
      // sample layer here: the later brick's. Within the tolerance; measured in rendering.md.)
      dense_keys_[std::size_t(pt.key.brick)] = pt.key;
      ++covered;
    }
  }
  // Every leaf brick drawn (a transparent one left out would be sampled here).
  return covered == octree.brick_count();
}

double VolumeRenderer::set_step_map(const tsp::FramePlan& plan, const RenderSettings& settings) {
  const tsp::Octree& octree = tree_.octree();
  if (!variation_) variation_.emplace(tf_, tree_.value_range());
  const std::array<int, 3> g = tsp::step_grid(octree.dims());
  cell_variation_.assign(std::size_t(g[0]) * g[1] * g[2], 0.f);
  cell_drawn_.assign(cell_variation_.size(), 0);
  for (const tsp::PlannedTexture& pt : plan.textures) {
    if (pt.deferred || pt.key.level != 0) continue;
    // Kept with the texture, and evicted with it.
    const tsp::CellVariations& c = textures_.variations(pt.key, [&] {
      const tsp::BrickSamples samples = texture_samples(bricks_, pt.key);
      return variation_->cells(samples->data(), octree.brick_samples(pt.key.brick));
    });
    for (int z = 0; z < c.count[2]; ++z)
      for (int y = 0; y < c.count[1]; ++y)
        for (int x = 0; x < c.count[0]; ++x) {
          const std::size_t i =
              (std::size_t(z + c.first[2]) * std::size_t(g[1]) + std::size_t(y + c.first[1])) *
                  std::size_t(g[0]) + std::size_t(x + c.first[0]);
          const float v = c.v[(std::size_t(z) * std::size_t(c.count[1]) + std::size_t(y)) *
                                  std::size_t(c.count[0]) + std::size_t(x)];
          cell_variation_[i] = std::max(cell_variation_[i], v);
          cell_drawn_[i] = 1;
        }
  }
  const std::vector<std::uint8_t> rows =
      tsp::step_rows(cell_variation_, g, settings.spacing, settings.sampling_tol);
  compositor_->set_step_map(rows, g, {tsp::kStepCell, tsp::kStepCell, tsp::kStepCell});
  double sum = 0;
  int count = 0;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (cell_drawn_[i]) {
      sum += tsp::kStepMultipliers[rows[i]];
      ++count;
    }
  return count ? sum / count : 1.0;
}

bool VolumeRenderer::leaf_clipped(int brick) const {
  return !clip_sides_.empty() &&
         clip_sides_[std::size_t(tree_.octree().brick_node(brick))] != tsp::ClipSide::kept;
}

void VolumeRenderer::fill_pages(const tsp::FramePlan& plan, tsp::FrameMetric& metric,
                                bool level_tf) {
  const tsp::Octree& octree = tree_.octree();
  const auto g = octree.brick_grid();
  pages_.reset(g, {octree.brick_cells(0), octree.brick_cells(1), octree.brick_cells(2)});
  soup_.clear();
  // The CPU caster reads the full-resolution bricks from one dense region, where it walks runs
  // of neighbouring bricks as one volume (BrickTextures::place_dense).
  bool dense_host = false;
  if (compositor_->cpu_frame() && dense_host_) {
    dense_host = textures_.place_dense(level0_keys(plan));
  }
  pages_.set_runs(dense_host);
  for (const tsp::PlannedNode& n : plan.nodes) {
    if (n.cls == tsp::DrawClass::not_rendered) continue;
    const int tsp_id = tree_.id(n.node.octree_id, n.node.time_id);
    if (n.cls == tsp::DrawClass::untextured) {
      const tsp::Rgba c = metric.mean_colour(tsp_id);
      octree.for_each_brick(n.node.octree_id, [&](int b) { pages_.set_flat(b, c); });
      continue;
    }
    for (int i = n.first_texture; i < n.first_texture + n.texture_count; ++i) {
      const tsp::PlannedTexture& pt = plan.textures[std::size_t(i)];
      // A level brick's slot serves every leaf page below its node.
      const int o = octree.stored_brick_node(pt.key.brick);
      if (pt.deferred) {  // not uploaded yet: the node's mean colour meanwhile
        const tsp::Rgba c = metric.mean_colour(tsp_id);
        octree.for_each_brick(o, [&](int b) { pages_.set_flat(b, c); });
      } else if (pt.key.level == 0) {
        pages_.set_textured(pt.key.brick, dense_host ? textures_.dense_at(pt.key) : textures_.at(pt.key),
                            leaf_clipped(pt.key.brick));
      } else {
        // A level brick: the full-resolution traversal still decides, leaf page by leaf page,
        // what is skipped (transparent) or drawn flat (coherent); the rest samples the level.
        const BrickSlot slot = textures_.at(pt.key);
        // Its TF row: the level's residual at this step, as a share of the TF's domain.
        const int row = level_tf ? tsp::level_tf_row(double(tree_.level_error(o, pt.key.t0)) /
                                                     tf_.domain().width())
                                 : 0;
        octree.for_each_brick(o, [&](int b) {
          const LeafShading& ls = leaf_shading_[std::size_t(b)];
          if (ls.shading == tsp::Shading::textured)
            pages_.set_textured(b, slot, leaf_clipped(b), row);
          else if (ls.shading == tsp::Shading::flat)
            pages_.set_flat(b, metric.mean_colour(ls.tsp_id));
        });
      }
    }
  }
  pages_.finish();
}

VolumeRenderer::Frame VolumeRenderer::plan(int step, const tsp::Camera& camera,
                                           const RenderSettings& requested,
                                           tsp::FrameMetric& metric, tsp::LodStops stops,
                                           const PartialFrame* part) {
  Frame f;
  f.part = part;
  // Probes clip per sample in the one-pass ray caster: frames with probes are ray cast.
  f.settings = requested;
  if (!clip_sides_.empty()) f.settings.compositing = Compositing::rays;
  const tsp::ViewOrder order = view_order(camera);
  // errors_for_step makes every node this step's traversal can reach current, so class_info and
  // mean_colour below only read memoised results.
  const tsp::NodeErrors& errors = metric.errors_for_step(step);
  const std::vector<tsp::Emitted> emitted =
      tsp::traverse(traversal(step, f.settings, metric, errors, order, stops));
  f.plan = tsp::plan_frame({.tree = tree_,
                            .step = step,
                            .emitted = emitted,
                            .info = tsp::node_info(metric),
                            .tol = f.settings.tol,
                            .view = order,
                            .upload_budget = f.settings.upload_budget,
                            .span_step = f.settings.span_step,
                            .stops = stops,
                            .clip_surface = clip_surface_},
                           cache_);
  shade_leaves(traversal(step, f.settings, metric, errors, order, {}), f, metric);
  decide_reuse(f, camera, metric);
  return f;
}

void VolumeRenderer::shade_leaves(const tsp::TraversalQuery& full, const Frame& f,
                                  tsp::FrameMetric& metric) {
  // Ray casting a level brick, each leaf page below it keeps the full-resolution traversal's
  // shading: skipped when transparent, flat when coherent (fill_pages).
  level_pages_.clear();
  const bool level_textures =
      std::any_of(f.plan.textures.begin(), f.plan.textures.end(),
                  [](const tsp::PlannedTexture& pt) { return pt.key.level > 0; });
  if (f.settings.compositing != Compositing::rays || !level_textures) return;
  const tsp::Octree& octree = tree_.octree();
  leaf_shading_.assign(std::size_t(octree.brick_count()), {});
  for (const tsp::Emitted& e : tsp::traverse(full)) {
    const int id = tree_.id(e.octree_id, e.time_id);
    // As plan_frame: clipped away → nothing; across the clip surface → sampled.
    const LeafShading ls{
        tsp::emitted_shading(tree_, e, metric.class_info(id), full.tol, {}, clip_surface_), id};
    octree.for_each_brick(e.octree_id, [&](int b) { leaf_shading_[std::size_t(b)] = ls; });
  }
  for (const LeafShading& ls : leaf_shading_)
    level_pages_.push_back(std::int64_t(ls.tsp_id + 1) * kShadingCount + int(ls.shading));
}

void VolumeRenderer::decide_reuse(Frame& f, const tsp::Camera& camera, tsp::FrameMetric& metric) {
  // Partial-image reuse: with the same view, TF and knobs as the last frame, only the screen
  // rectangles of the bricks drawn differently are drawn again.
  f.ids = brick_identities(
      tree_, f.plan, [&](int id) { return metric.mean_colour(id); }, level_pages_);
  f.key = reuse_key(camera, f.settings);
  f.reuse = f.settings.reuse_image && !(f.settings.surface && compositor_->has_surface()) &&
            f.settings.render_scale == 1 && previous_ &&
            previous_->key == f.key;
  if (f.part) {  // a partial frame: its rectangles, over the picture kept
    f.reuse = true;
    f.rects = f.part->rects;
    previous_.reset();
    return;
  }
  if (f.reuse) {
    BrickIdentities before = previous_->ids;
    if (f.settings.shade) {
      // Lit samples take their gradients one texel across brick faces (the caster reads the
      // neighbour brick there), so a brick beside one that changed is drawn again too.
      const tsp::Octree& octree = tree_.octree();
      const std::array<int, 3> g = octree.brick_grid();
      std::vector<char> beside(before.size(), 0);
      for (int b = 0; b < octree.brick_count(); ++b) {
        if (before[std::size_t(b)] == f.ids[std::size_t(b)]) continue;
        const std::array<int, 3> c = octree.brick_coord(b);
        for (int a = 0; a < 3; ++a)
          for (int d : {-1, 1}) {
            std::array<int, 3> n = c;
            n[std::size_t(a)] += d;
            if (n[std::size_t(a)] < 0 || n[std::size_t(a)] >= g[std::size_t(a)]) continue;
            beside[std::size_t(n[0] + g[0] * (n[1] + g[1] * n[2]))] = 1;
          }
      }
      for (std::size_t b = 0; b < beside.size(); ++b)
        if (beside[b]) before[b] = {~f.ids[b][0], f.ids[b][1]};  // differs: drawn again
    }
    f.rects = dirty_rects(tree_, camera, before, f.ids);
  }
  previous_.reset();  // valid again only once this frame is complete
}

void VolumeRenderer::upload(const Frame& f, FrameReport& r) {
  // Uploads first (growing the atlas moves every slot), then the draw list or the brick pages.
  for (const tsp::TextureKey& k : f.plan.evict_before) textures_.erase(k);
  for (const tsp::PlannedTexture& pt : f.plan.textures)
    if (!pt.deferred && pt.upload) textures_.upload(pt.key);
  // The texels neighbouring bricks share hold one brick's sample in every slot, whichever
  // steps' textures the two are drawn from (BrickTextures::stitch).
  r.bytes_stitched = textures_.stitch(level0_keys(f.plan));
  r.dense = f.settings.compositing == Compositing::rays && f.settings.dense && dense_frame(f.plan);
  // Every leaf brick textured at full resolution from one step: the whole volume as one page.
  if (r.dense) dense_.update(dense_keys_);
}

tsp::Aabb VolumeRenderer::drawn_bounds(const tsp::FramePlan& plan) const {
  const tsp::Octree& octree = tree_.octree();
  // The rays go through the bounds of what is drawn: transparent and clipped bricks around it
  // cost no fragments and no leaps.
  tsp::Aabb drawn = tsp::empty_aabb();
  for (const tsp::PlannedNode& n : plan.nodes)
    if (n.cls != tsp::DrawClass::not_rendered && n.cls != tsp::DrawClass::clipped)
      tsp::unite(drawn, tsp::geometric_box(octree.node(n.node.octree_id).box, octree.dims()));
  // And through the clip solid's bounds there (the bricks across its surface stick out of it) —
  // without a surface to draw: the caster finds the surface where a ray enters the solid after
  // its start, which a ray starting on it would miss.
  if (!clip_sides_.empty() && !clip_surface_ && !tsp::is_empty(drawn)) drawn = clip_.bound(drawn);
  return drawn;
}

void VolumeRenderer::compose(const Frame& f, const tsp::Camera& camera, tsp::FrameMetric& metric,
                             FrameReport& r) {
  const tsp::Octree& octree = tree_.octree();
  const bool rays = f.settings.compositing == Compositing::rays;
  const tsp::Aabb drawn = drawn_bounds(f.plan);
  const tsp::Aabb* bounds = tsp::is_empty(drawn) ? nullptr : &drawn;
  if (r.dense) {
    pages_.reset({1, 1, 1}, {std::max(octree.dims().x - 1, 1), std::max(octree.dims().y - 1, 1),
                             std::max(octree.dims().z - 1, 1)});
    pages_.set_textured(0, dense_.slot(), !clip_sides_.empty());
    pages_.finish();
    compositor_->set_pages(pages_, octree.dims(), bounds);
  } else if (rays) {
    fill_pages(f.plan, metric, f.settings.level_tf);
    compositor_->set_pages(pages_, octree.dims(), bounds);
  } else {
    fill_items(f.plan, metric, camera, f.settings);
  }
  if (rays && compositor_->adaptive()) r.step_multiplier = set_step_map(f.plan, f.settings);
  r.polygons = std::int64_t(soup_.size());
}

void VolumeRenderer::draw(Frame& f, const tsp::Camera& camera, FrameReport& r) {
  const RenderSettings& settings = f.settings;
  auto draw_all = [&] {
    if (settings.compositing == Compositing::rays)
      compositor_->draw_rays();
    else
      compositor_->draw(items_);
  };
  if (!f.reuse) {
    draw_all();
  } else {
    std::int64_t area = 0;
    for (const PixelRect& rect : f.rects) {
      compositor_->set_region(rect, settings);
      draw_all();
      area += rect.area();
    }
    compositor_->set_region(PixelRect{}, settings);
    r.redrawn_percent = 100.0 * double(area) /
                        double(std::max(1, camera.params().width * camera.params().height));
  }
  if (settings.compositing == Compositing::rays)
    r.boxes = 1;
  else
    for (const DrawItem& it : items_) r.boxes += it.as_box;
  for (const tsp::TextureKey& k : f.plan.release_after) textures_.erase(k);
  r.fragments = compositor_->end_frame();
  if (!f.part) {
    previous_ = Previous{f.key, std::move(f.ids)};
    partial_.reset();
    return;
  }
  // A partial frame: the picture is whole (and reusable) once its parts since the first were
  // all drawn with the same inputs.
  if (f.part->first || !partial_) {
    partial_same_ = f.part->first;
    partial_ = Previous{f.key, f.ids};
  } else if (!(partial_->key == f.key && partial_->ids == f.ids)) {
    partial_same_ = false;
    partial_ = Previous{f.key, f.ids};
  }
  r.partial_stale = !partial_same_;
  if (f.part->completes && partial_same_) previous_ = partial_;
}

void VolumeRenderer::report(const tsp::FramePlan& plan, FrameReport& r) const {
  for (int c = 0; c < tsp::kDrawClassCount; ++c)
    r.class_percent[std::size_t(c)] = plan.percent(tsp::DrawClass(c));
  r.bytes_uploaded = plan.bytes_uploaded;
  r.textures_resident = plan.textures_resident;
  r.texture_bytes = plan.texture_bytes;
  r.deferred_textures = plan.deferred;
  // Which steps the picture stands for, and which steps' bricks it shows.
  r.spans_lo = r.spans_hi = r.shown_lo = r.shown_hi = plan.step;
  for (const tsp::PlannedNode& n : plan.nodes) {
    if (n.cls == tsp::DrawClass::not_rendered) continue;
    const tsp::Span sp = tree_.time().span(n.node.time_id);
    r.spans_lo = std::min(r.spans_lo, sp.t0);
    r.spans_hi = std::max(r.spans_hi, sp.t1);
    for (int i = n.first_texture; i < n.first_texture + n.texture_count; ++i) {
      const tsp::TextureKey& k = plan.textures[std::size_t(i)].key;
      r.shown_lo = std::min(r.shown_lo, k.t0);
      r.shown_hi = std::max(r.shown_hi, k.last_step());
      r.shows_mean |= k.is_mean();
    }
  }
}

FrameReport VolumeRenderer::render(int step, const tsp::Camera& camera,
                                   const RenderSettings& requested, tsp::FrameMetric& metric,
                                   tsp::LodStops stops, const PartialFrame* part) {
  const tsp::Stopwatch frame;
  FrameReport r;
  r.step = step;
  tsp::Stopwatch phase;
  RenderSettings asked = requested;
  if (part) asked.render_scale = 1;  // the parts are drawn at full size
  Frame f = plan(step, camera, asked, metric, stops, part);
  r.traversal_ms = phase.lap_ms();
  compositor_->begin_frame(camera, f.settings, f.reuse);
  if (compositor_->cpu_frame()) {  // the CPU caster reads the textures' texels in RAM
    textures_.set_host_mirror(true);
    dense_.set_host_mirror(true);
  }
  r.backend = compositor_->cpu_frame() ? "cpu" : "gl";
  r.backend_note = compositor_->backend_note();
  upload(f, r);
  r.upload_ms = phase.lap_ms();
  compose(f, camera, metric, r);
  r.slicing_ms = phase.lap_ms();
  draw(f, camera, r);
  r.draw_ms = phase.lap_ms();
  r.samples = compositor_->cpu_samples();
  r.ms = frame.ms();
  report(f.plan, r);
  return r;
}

}  // namespace tspgl

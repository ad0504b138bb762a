#include "render/volume_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>

#include "gl/gl_error.h"
#include "tsp/frame/slicer.h"
#include "tsp/tree/traversal.h"

namespace tspgl {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

constexpr int kVolumeUnit = 0;  // texture unit of the brick (or whole-volume) texture
constexpr int kTfUnit = 1;      // texture unit of the transfer-function lookup

// Opacity for a slice spacing of `spacing` voxels when the TF's opacity is per voxel (spec §9).
float corrected_alpha(float alpha, double spacing) {
  return float(1.0 - std::pow(1.0 - std::clamp(double(alpha), 0.0, 1.0), spacing));
}

tsp::ViewOrder view_order(const tsp::Camera& camera) {
  return camera.perspective() ? tsp::ViewOrder::perspective(camera.eye())
                              : tsp::ViewOrder::orthographic(camera.direction());
}

}  // namespace

VolumeRenderer::VolumeRenderer(GlContext& ctx, const tsp::TspFile& file, tsp::CachePolicy cache,
                               std::int64_t texture_budget, std::int64_t brick_budget)
    : ctx_(ctx),
      gl_(ctx.gl()),
      file_(file),
      cache_(texture_budget, cache),
      bricks_(file, brick_budget),
      textured_(load_program(ctx.gl(), "slice.vert", "slice_textured.frag")),
      flat_(load_program(ctx.gl(), "slice.vert", "slice_flat.frag")) {
  gl_.GenVertexArrays(1, &vao_);
  gl_.BindVertexArray(vao_);
  gl_.GenBuffers(1, &vbo_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  gl_.EnableVertexAttribArray(0);
  gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  gl_.GenTextures(1, &tf_texture_);
  textured_.use();
  gl_.Uniform1i(textured_.uniform("volume"), kVolumeUnit);
  gl_.Uniform1i(textured_.uniform("transfer_function"), kTfUnit);
  // 16-bit rows of odd width are not 4-byte aligned.
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  check_gl(gl_, "setting up the volume renderer");
}

VolumeRenderer::~VolumeRenderer() {
  clear_textures();
  if (fbo_) gl_.DeleteFramebuffers(1, &fbo_);
  if (fbo_colour_) gl_.DeleteRenderbuffers(1, &fbo_colour_);
  if (baseline_texture_) gl_.DeleteTextures(1, &baseline_texture_);
  gl_.DeleteTextures(1, &tf_texture_);
  gl_.DeleteBuffers(1, &vbo_);
  gl_.DeleteVertexArrays(1, &vao_);
}

void VolumeRenderer::set_transfer_function(const tsp::TransferFunction& tf) {
  tf_entries_.assign(tf.entries().begin(), tf.entries().end());
  tf_spacing_ = -1;  // re-uploaded, corrected for the spacing, by the next frame
  // A normalised code s means v = q.lo + s·q.width; its TF coordinate is (v − tf.lo)/tf.width.
  const tsp::ValueRange q = file_.tree().value_range(), d = tf.domain();
  tf_scale_ = q.width() / d.width();
  tf_offset_ = (q.lo - d.lo) / d.width();
}

// The lookup texture holds, per entry, the colour premultiplied by the opacity corrected for the
// slice spacing. Nearest lookup: the rendered TF is exactly the K-entry table the metrics and the
// exact transparency test reason about (entry_of = floor(u·K)).
void VolumeRenderer::upload_tf(double spacing) {
  if (spacing == tf_spacing_) return;
  std::vector<float> rgba;
  rgba.reserve(tf_entries_.size() * 4);
  for (const tsp::Rgba& e : tf_entries_) {
    const float a = corrected_alpha(e.a, spacing);
    rgba.insert(rgba.end(), {e.r * a, e.g * a, e.b * a, a});
  }
  gl_.ActiveTexture(GL_TEXTURE0 + kTfUnit);
  gl_.BindTexture(GL_TEXTURE_1D, tf_texture_);
  gl_.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl_.TexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, GLsizei(tf_entries_.size()), 0, GL_RGBA, GL_FLOAT,
                 rgba.data());
  gl_.ActiveTexture(GL_TEXTURE0 + kVolumeUnit);
  check_gl(gl_, "uploading the transfer function");
  tf_spacing_ = spacing;
}

void VolumeRenderer::clear_textures() {
  for (auto& [key, id] : textures_) gl_.DeleteTextures(1, &id);
  textures_.clear();
  cache_.clear();
}

int VolumeRenderer::drop_unreachable(const tsp::MetricResult& metric, const tsp::Tolerances& tol) {
  const auto dropped =
      cache_.drop_unreachable(tsp::reachable_textures(file_.tree(), metric, tol));
  for (const tsp::TextureKey& k : dropped) delete_texture(k);
  return int(dropped.size());
}

std::vector<tsp::BrickKey> VolumeRenderer::bricks_needed(int step, const tsp::Camera& camera,
                                                         const RenderSettings& settings,
                                                         const tsp::NodeErrors& errors,
                                                         const tsp::NodeInfoFn& info) const {
  const tsp::TspTree& tree = file_.tree();
  const tsp::ViewOrder order = view_order(camera);
  std::vector<tsp::BrickKey> keys;
  for (const tsp::Emitted& e : tsp::traverse(tree, step, settings.tol, errors, order)) {
    const int id = tree.id(e.octree_id, e.time_id);
    if (tsp::shading_of(info(id), settings.tol) != tsp::Shading::textured) continue;
    for (int brick : tsp::leaf_bricks(tree.octree(), e.octree_id, order))
      if (!textures_.contains(tsp::TextureKey{brick, e.span.t0, 0}))
        keys.push_back({brick, e.span.t0});
  }
  return keys;
}

std::vector<tsp::BrickKey> VolumeRenderer::bricks_to_upload(int step, const tsp::Camera& camera,
                                                            const RenderSettings& settings,
                                                            tsp::LazyErrors& metric) const {
  const tsp::NodeErrors& errors = metric.errors_for_step(step);
  auto info = [&metric](int id) {
    const tsp::NodeResult& n = metric.node(id);
    return tsp::NodeClassInfo{n.spatial, n.transparent};
  };
  return bricks_needed(step, camera, settings, errors, info);
}

std::vector<tsp::BrickKey> VolumeRenderer::bricks_to_upload(
    int step, const tsp::Camera& camera, const RenderSettings& settings,
    const tsp::MetricResult& metric) const {
  return bricks_needed(step, camera, settings, metric.errors, tsp::node_info(metric));
}

int VolumeRenderer::drop_unreachable(tsp::LazyErrors& metric, const tsp::Tolerances& tol) {
  const tsp::NodeErrors& errors = metric.all();
  auto info = [&metric](int id) {
    const tsp::NodeResult& n = metric.node(id);
    return tsp::NodeClassInfo{n.spatial, n.transparent};
  };
  const auto dropped =
      cache_.drop_unreachable(tsp::reachable_textures(file_.tree(), errors, info, tol));
  for (const tsp::TextureKey& k : dropped) delete_texture(k);
  return int(dropped.size());
}

void VolumeRenderer::delete_texture(const tsp::TextureKey& key) {
  auto it = textures_.find(key);
  if (it == textures_.end()) return;
  gl_.DeleteTextures(1, &it->second);
  textures_.erase(it);
}

GLuint VolumeRenderer::upload_brick(int brick, int step) {
  tsp::BrickSamples samples = bricks_.get(brick, step);
  const tsp::Box s = file_.tree().octree().brick_samples(brick);
  return create_scalar_texture(s.size(0), s.size(1), s.size(2), samples->data());
}

// A trilinear, edge-clamped 16-bit scalar texture of w × h × d samples (x fastest).
GLuint VolumeRenderer::create_scalar_texture(int w, int h, int d, const std::uint16_t* data) {
  GLuint id = 0;
  gl_.GenTextures(1, &id);
  gl_.BindTexture(GL_TEXTURE_3D, id);
  gl_.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl_.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    gl_.TexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
  gl_.TexImage3D(GL_TEXTURE_3D, 0, GL_R16, w, h, d, 0, GL_RED, GL_UNSIGNED_SHORT, data);
  return id;
}

// Slices are composited in a 16-bit-per-channel colour buffer: in 8 bits each thin slice's
// premultiplied contribution (a few 1/255 steps) is rounded, and over hundreds of slices the
// error reaches ΔE 10 (tests/render: the constant cube). The result is blitted (converted) to the
// context's default framebuffer once per frame.
void VolumeRenderer::ensure_target() {
  if (fbo_ && fbo_width_ == ctx_.width() && fbo_height_ == ctx_.height()) return;
  if (!fbo_) gl_.GenFramebuffers(1, &fbo_);
  if (!fbo_colour_) gl_.GenRenderbuffers(1, &fbo_colour_);
  gl_.BindRenderbuffer(GL_RENDERBUFFER, fbo_colour_);
  // RGBA16 (unorm) blends fastest on llvmpipe of RGBA16/16F/32F and keeps 16 bits.
  gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA16, ctx_.width(), ctx_.height());
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, fbo_colour_);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw tsp::GlError("the 16-bit render target (RGBA16 framebuffer) is not supported");
  fbo_width_ = ctx_.width();
  fbo_height_ = ctx_.height();
}

void VolumeRenderer::end_frame() {
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  gl_.BlitFramebuffer(0, 0, fbo_width_, fbo_height_, 0, 0, fbo_width_, fbo_height_,
                      GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void VolumeRenderer::begin_frame(const tsp::Camera& camera, const RenderSettings& settings) {
  ctx_.make_current();
  ensure_target();
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.Viewport(0, 0, ctx_.width(), ctx_.height());
  gl_.ClearColor(settings.background[0], settings.background[1], settings.background[2], 1.f);
  gl_.Clear(GL_COLOR_BUFFER_BIT);
  gl_.Disable(GL_DEPTH_TEST);
  gl_.Disable(GL_CULL_FACE);
  gl_.Enable(GL_BLEND);
  // Premultiplied colours composited back to front with "over"; alpha stays 1 (opaque image).
  gl_.BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  gl_.BindVertexArray(vao_);
  const glm::mat4 vp(camera.view_projection());
  for (const Program* p : {&textured_, &flat_}) {
    p->use();
    gl_.UniformMatrix4fv(p->uniform("view_projection"), 1, GL_FALSE, glm::value_ptr(vp));
  }
  textured_.use();
  gl_.Uniform2f(textured_.uniform("tf_map"), float(tf_scale_), float(tf_offset_));
  upload_tf(settings.spacing);
  gl_.ActiveTexture(GL_TEXTURE0 + kTfUnit);
  gl_.BindTexture(GL_TEXTURE_1D, tf_texture_);
  gl_.ActiveTexture(GL_TEXTURE0 + kVolumeUnit);
}

void VolumeRenderer::upload_vertices() {
  vertices_.assign(soup_.xyz.begin(), soup_.xyz.end());
  firsts_.resize(soup_.size());
  counts_.resize(soup_.size());
  GLint next = 0;
  for (std::size_t i = 0; i < soup_.size(); ++i) {
    firsts_[i] = next;
    counts_[i] = GLsizei(soup_.counts[i]);
    next += counts_[i];
  }
  gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices_.size() * sizeof(float)), vertices_.data(),
                 GL_STREAM_DRAW);
}

void VolumeRenderer::draw_items(const std::vector<DrawItem>& items,
                                const std::vector<GLuint>& textures,
                                const std::vector<tsp::Box>& sample_boxes) {
  const Program* current = nullptr;
  for (const DrawItem& it : items) {
    if (it.polygon_count == 0) continue;
    const Program* want = it.texture >= 0 ? &textured_ : &flat_;
    if (want != current) {
      want->use();
      current = want;
    }
    if (it.texture >= 0) {
      const tsp::Box& s = sample_boxes[std::size_t(it.texture)];
      gl_.BindTexture(GL_TEXTURE_3D, textures[std::size_t(it.texture)]);
      gl_.Uniform3f(textured_.uniform("tex_origin"), float(s.lo[0]) - 0.5f,
                    float(s.lo[1]) - 0.5f, float(s.lo[2]) - 0.5f);
      gl_.Uniform3f(textured_.uniform("tex_scale"), 1.f / float(s.size(0)),
                    1.f / float(s.size(1)), 1.f / float(s.size(2)));
    } else {
      gl_.Uniform4fv(flat_.uniform("flat_colour"), 1, it.colour.data());
    }
    gl_.MultiDrawArrays(GL_TRIANGLE_FAN, firsts_.data() + it.first_polygon,
                        counts_.data() + it.first_polygon, it.polygon_count);
  }
}

FrameReport VolumeRenderer::render(int step, const tsp::Camera& camera,
                                   const RenderSettings& settings,
                                   const tsp::MetricResult& metric) {
  return render_tree(step, camera, settings, metric.errors, tsp::node_info(metric),
                     [&metric](int id) { return metric.mean_colour[std::size_t(id)]; });
}

FrameReport VolumeRenderer::render(int step, const tsp::Camera& camera,
                                   const RenderSettings& settings, tsp::LazyErrors& metric) {
  const tsp::NodeErrors& errors = metric.errors_for_step(step);
  // errors_for_step made every node this step's traversal can reach current, so node(id) below
  // only reads memoised results.
  auto info = [&metric](int id) {
    const tsp::NodeResult& n = metric.node(id);
    return tsp::NodeClassInfo{n.spatial, n.transparent};
  };
  return render_tree(step, camera, settings, errors, info,
                     [&metric](int id) { return metric.node(id).mean; });
}

FrameReport VolumeRenderer::render_tree(int step, const tsp::Camera& camera,
                                        const RenderSettings& settings,
                                        const tsp::NodeErrors& errors, const tsp::NodeInfoFn& info,
                                        const ColourFn& colour) {
  const auto t_frame = Clock::now();
  const tsp::TspTree& tree = file_.tree();
  const tsp::Octree& octree = tree.octree();
  FrameReport r;
  r.step = step;
  begin_frame(camera, settings);

  auto t0 = Clock::now();
  const tsp::ViewOrder order = view_order(camera);
  const std::vector<tsp::Emitted> emitted =
      tsp::traverse(tree, step, settings.tol, errors, order);
  const tsp::FramePlan plan =
      tsp::plan_frame(tree, step, emitted, info, settings.tol, order, cache_);
  r.traversal_ms = ms_since(t0);

  // Uploads over the frame's budget wait for later frames; the first upload always goes ahead
  // so that repeated frames of one step complete.
  std::vector<std::uint8_t> deferred(plan.textures.size(), 0);
  tsp::TextureKeySet deferred_keys;
  std::int64_t deferred_bytes = 0;
  if (settings.upload_budget > 0) {
    std::int64_t planned = 0;
    bool first = true;
    for (std::size_t i = 0; i < plan.textures.size(); ++i) {
      const tsp::PlannedTexture& pt = plan.textures[i];
      if (!pt.upload) continue;
      if (!first && planned + pt.bytes > settings.upload_budget) {
        deferred[i] = 1;
        deferred_keys.insert(pt.key);
        deferred_bytes += pt.bytes;
        continue;
      }
      planned += pt.bytes;
      first = false;
    }
  }

  t0 = Clock::now();
  const tsp::IncrementalSlicer slicer(tsp::SlicePlanes::toward(camera.direction(), settings.spacing));
  soup_.clear();
  std::vector<DrawItem> items;
  std::vector<tsp::Box> sample_boxes(plan.textures.size());
  auto add = [&](const tsp::Aabb& box, int texture, std::array<float, 4> colour) {
    DrawItem it;
    it.first_polygon = int(soup_.size());
    slicer.slice(box, soup_);
    it.polygon_count = int(soup_.size()) - it.first_polygon;
    it.texture = texture;
    it.colour = colour;
    items.push_back(it);
  };
  for (const tsp::PlannedNode& n : plan.nodes) {
    if (n.cls == tsp::DrawClass::not_rendered) continue;
    const int tsp_id = tree.id(n.node.octree_id, n.node.time_id);
    if (n.cls == tsp::DrawClass::untextured) {
      const tsp::Rgba c = colour(tsp_id);
      const float a = corrected_alpha(c.a, settings.spacing);
      add(tsp::geometric_box(octree.node(n.node.octree_id).box, octree.dims()), -1,
          {c.r * a, c.g * a, c.b * a, a});
      continue;
    }
    for (int i = n.first_texture; i < n.first_texture + n.texture_count; ++i) {
      const int brick = plan.textures[std::size_t(i)].key.brick;
      const tsp::Aabb box = tsp::geometric_box(octree.brick_box(brick), octree.dims());
      if (deferred[std::size_t(i)]) {  // not uploaded yet: the node's mean colour meanwhile
        const tsp::Rgba c = colour(tsp_id);
        const float a = corrected_alpha(c.a, settings.spacing);
        add(box, -1, {c.r * a, c.g * a, c.b * a, a});
        continue;
      }
      sample_boxes[std::size_t(i)] = octree.brick_samples(brick);
      add(box, i, {});
    }
  }
  upload_vertices();
  r.slicing_ms = ms_since(t0);
  r.polygons = std::int64_t(soup_.size());

  for (const tsp::TextureKey& k : plan.evict_before) delete_texture(k);
  t0 = Clock::now();
  std::vector<GLuint> textures(plan.textures.size(), 0);
  for (std::size_t i = 0; i < plan.textures.size(); ++i) {
    const tsp::PlannedTexture& pt = plan.textures[i];
    if (deferred[i]) continue;
    if (pt.upload) {
      delete_texture(pt.key);
      textures_[pt.key] = upload_brick(pt.key.brick, pt.key.t0);
    }
    textures[i] = textures_.at(pt.key);
  }
  r.upload_ms = ms_since(t0);

  t0 = Clock::now();
  draw_items(items, textures, sample_boxes);
  for (const tsp::TextureKey& k : plan.release_after) delete_texture(k);
  end_frame();
  ctx_.finish();
  r.draw_ms = ms_since(t0);
  r.ms = ms_since(t_frame);

  for (int c = 0; c < tsp::kDrawClassCount; ++c)
    r.class_percent[std::size_t(c)] = plan.percent(tsp::DrawClass(c));
  r.bytes_uploaded = plan.bytes_uploaded - deferred_bytes;
  r.textures_resident = plan.textures_resident;
  r.texture_bytes = plan.texture_bytes;
  if (!deferred_keys.empty()) {
    // The plan entered the deferred keys into the cache; they have no GL texture yet.
    const auto dropped =
        cache_.drop_unreachable([&](const tsp::TextureKey& k) { return !deferred_keys.count(k); });
    for (const tsp::TextureKey& k : dropped) {
      --r.textures_resident;
      r.texture_bytes -= tsp::texture_bytes(octree, k);
    }
    r.deferred_textures = std::int64_t(deferred_keys.size());
  }
  return r;
}

FrameReport VolumeRenderer::render_baseline(int step, const tsp::Camera& camera,
                                            const RenderSettings& settings) {
  const auto t_frame = Clock::now();
  const tsp::Octree& octree = file_.tree().octree();
  const tsp::Dims d = octree.dims();
  FrameReport r;
  r.step = step;
  begin_frame(camera, settings);

  // The whole step, assembled from the bricks and uploaded as one texture, every frame.
  auto t0 = Clock::now();
  volume_.resize(std::size_t(d.count()));
  for (int b = 0; b < octree.brick_count(); ++b) {
    tsp::BrickSamples samples = bricks_.get(b, step);
    const tsp::Box s = octree.brick_samples(b);
    const std::uint16_t* src = samples->data();
    for (int z = s.lo[2]; z < s.hi[2]; ++z)
      for (int y = s.lo[1]; y < s.hi[1]; ++y, src += s.size(0))
        std::memcpy(volume_.data() + s.lo[0] + std::size_t(d.x) * (y + std::size_t(d.y) * z), src,
                    std::size_t(s.size(0)) * sizeof(std::uint16_t));
  }
  if (baseline_texture_) gl_.DeleteTextures(1, &baseline_texture_);
  baseline_texture_ = create_scalar_texture(d.x, d.y, d.z, volume_.data());
  r.upload_ms = ms_since(t0);
  r.bytes_uploaded = d.count() * std::int64_t(sizeof(std::uint16_t));
  r.textures_resident = 1;
  r.texture_bytes = r.bytes_uploaded;

  t0 = Clock::now();
  const tsp::IncrementalSlicer slicer(tsp::SlicePlanes::toward(camera.direction(), settings.spacing));
  soup_.clear();
  const tsp::Box whole{{0, 0, 0}, {d.x, d.y, d.z}};
  DrawItem item;
  slicer.slice(tsp::geometric_box(whole, d), soup_);
  item.polygon_count = int(soup_.size());
  item.texture = 0;
  upload_vertices();
  r.slicing_ms = ms_since(t0);
  r.polygons = std::int64_t(soup_.size());

  t0 = Clock::now();
  draw_items({item}, {baseline_texture_}, {whole});
  end_frame();
  ctx_.finish();
  r.draw_ms = ms_since(t0);
  r.ms = ms_since(t_frame);
  r.class_percent[std::size_t(tsp::DrawClass::new_texture)] = 100.0;
  return r;
}

}  // namespace tspgl

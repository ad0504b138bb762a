#include "render/slice_compositor.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <initializer_list>
#include <glm/gtc/type_ptr.hpp>
#include <string>

#include "gl/gl_error.h"
#include "gl/gl_objects.h"
#include "tsp/frame/refine.h"
#include "tsp/frame/sample_steps.h"
#include "tsp/metric/level_tf.h"

namespace tspgl {

namespace {
constexpr int kVolumeUnit = 0;  // texture unit of the brick (or whole-volume) texture
constexpr int kTfUnit = 1;      // texture unit of the transfer-function lookup
constexpr int kPagesUnit = 2;   // texture unit of the ray caster's brick pages
constexpr int kPreintegratedUnit = 3;  // texture unit of the pre-integrated TF table
constexpr int kSurfaceTfUnit = 4;      // texture unit of the clip surface's colours
constexpr int kStepMapUnit = 5;        // texture unit of adaptive sampling's per-brick steps
constexpr int kTfRowsUnit = 6;         // texture unit of adaptive sampling's TF rows
constexpr int kLevelTfUnit = 7;        // texture unit of the coarse levels' TF rows
constexpr int kSurfaceDepthUnit = 8;    // texture unit of the surface splats' depths
constexpr int kRefineUnit = 9;          // texture unit of refinement's TF table
// Clears the bound target (or the scissored part of it) to the opaque background.
void clear(const GlApi& gl, const RenderSettings& settings) {
  gl.ClearColor(settings.background[0], settings.background[1], settings.background[2], 1.f);
  gl.Clear(GL_COLOR_BUFFER_BIT);
}

// The unit cube's 12 triangles, counter-clockwise seen from outside.
std::vector<float> cube_triangles() {
  static constexpr int kFaces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                       {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  std::vector<float> v;
  auto corner = [&](int c) { v.insert(v.end(), {float(c & 1), float(c >> 1 & 1), float(c >> 2 & 1)}); };
  for (const auto& f : kFaces)
    for (int i : {0, 2, 1, 0, 3, 2}) corner(f[i]);  // the faces above run clockwise
  return v;
}
constexpr GLsizei kCubeVertices = 36;
}  // namespace

std::array<float, 4> flat_colour(const tsp::Rgba& c, double spacing) {
  const float a = tsp::corrected_opacity(c.a, spacing);
  return {c.r * a, c.g * a, c.b * a, a};
}

SliceCompositor::SliceCompositor(GlContext& ctx)
    : ctx_(ctx),
      gl_(ctx.gl()),
      textured_(load_program_with(ctx.gl(), "slice.vert", "slice_textured.frag",
                                  {"sample_tf.glsl"}, glsl_constants())),
      flat_(load_program(ctx.gl(), "slice.vert", "slice_flat.frag")),
      box_textured_(load_program_with(ctx.gl(), "box.vert", "box_textured.frag",
                                      {"box_ray.glsl", "sample_tf.glsl"}, glsl_constants())),
      box_flat_(load_program_with(ctx.gl(), "box.vert", "box_flat.frag", {"box_ray.glsl"})),
      ray_programs_(ctx.gl(), [this](const Program& p) { set_units(p); }),
      tf_(ctx.gl()),
      surface_tf_(ctx.gl()),
      target_(ctx) {
  make_vertex_array(gl_, cube_vao_, cube_vbo_, 3, cube_triangles());
  make_vertex_array(gl_, vao_, vbo_, 3);
  for (const Program* p : {&textured_, &box_textured_}) set_units(*p);
  rays_ = &ray_programs_.get(RayVariant::segments);
  gl_.GenQueries(1, &fragments_query_);
  software_gl_ = software_renderer(ctx_.describe());
  for (GLuint* t : {&pages_, &step_map_}) {
    gl_.GenTextures(1, t);
    gl_.BindTexture(GL_TEXTURE_3D, *t);
    gl_.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  gl_.BindTexture(GL_TEXTURE_3D, step_map_);
  for (GLenum w : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    gl_.TexParameteri(GL_TEXTURE_3D, w, GL_CLAMP_TO_EDGE);
  check_gl(gl_, "setting up the slice compositor");
}

SliceCompositor::~SliceCompositor() {
  gl_.DeleteBuffers(1, &vbo_);
  gl_.DeleteVertexArrays(1, &vao_);
  gl_.DeleteBuffers(1, &cube_vbo_);
  gl_.DeleteTextures(1, &pages_);
  gl_.DeleteTextures(1, &step_map_);
  gl_.DeleteQueries(1, &fragments_query_);
  gl_.DeleteVertexArrays(1, &cube_vao_);
}

void SliceCompositor::set_transfer_function(const tsp::TransferFunction& tf,
                                            tsp::ValueRange quantized, std::vector<double> prior) {
  tf_.set(tf, quantized, std::move(prior));
}

void SliceCompositor::set_units(const Program& p) {
  p.use();
  gl_.Uniform1i(p.uniform("volume"), kVolumeUnit);
  gl_.Uniform1i(p.uniform("transfer_function"), kTfUnit);
  gl_.Uniform1i(p.uniform("preintegrated"), kPreintegratedUnit);
  gl_.Uniform1i(p.uniform("pages"), kPagesUnit);
  gl_.Uniform1i(p.uniform("surface_tf"), kSurfaceTfUnit);
  gl_.Uniform1i(p.uniform("step_map"), kStepMapUnit);
  gl_.Uniform1i(p.uniform("tf_rows"), kTfRowsUnit);
  gl_.Uniform1i(p.uniform("level_tfs"), kLevelTfUnit);
  gl_.Uniform1i(p.uniform("surface_depth"), kSurfaceDepthUnit);
  gl_.Uniform1i(p.uniform("tf_refine"), kRefineUnit);
}

void SliceCompositor::set_clip(const tsp::ClipRegion& clip, const tsp::TransferFunction* surface,
                               tsp::ValueRange quantized) {
  clip_region_ = clip;
  const int n = int(clip.probes().size());
  // The clipping caster is its own variant, built the first time a probe is used: its code
  // costs llvmpipe's shader compiler seconds, which frames without probes should not pay.
  // An intersection keeps one interval of each ray: a leaner variant that cuts the ray to it
  // and draws the surface at its ends (the general one costs llvmpipe about twice per pixel and
  // more per sample, since every branch runs under a mask).
  clipping_ = n > 0;
  clip_variant_ = clip.op() == tsp::ProbeOp::intersect ? RayVariant::clipped_interval
                                                        : RayVariant::clipped;
  rays_ = &ray_programs_.get(clipping_ ? clip_variant_ : RayVariant::segments);
  rays_->use();
  gl_.Uniform1i(rays_->uniform("clip_count"), n);
  surface_on_ = n > 0 && surface;
  gl_.Uniform1i(rays_->uniform("clip_surface"), surface_on_ ? 1 : 0);
  if (n == 0) return;
  std::vector<GLint> kind(static_cast<std::size_t>(n));
  std::vector<float> a(std::size_t(n) * 4), size(std::size_t(n) * 3), rot(std::size_t(n) * 9);
  for (int i = 0; i < n; ++i) {
    const tsp::Probe& p = clip.probes()[std::size_t(i)];
    kind[std::size_t(i)] = int(p.kind);
    for (int c = 0; c < 3; ++c) {
      a[std::size_t(4 * i + c)] = float(p.centre[std::size_t(c)]);
      size[std::size_t(3 * i + c)] = float(p.size[std::size_t(c)]);
    }
    a[std::size_t(4 * i + 3)] = float(p.radius);
    for (int c = 0; c < 9; ++c)
      rot[std::size_t(9 * i + c)] = float(clip.rotations()[std::size_t(i)][std::size_t(c)]);
  }
  gl_.Uniform1i(rays_->uniform("clip_op"), int(clip.op()));
  gl_.Uniform1iv(rays_->uniform("clip_kind"), n, kind.data());
  gl_.Uniform4fv(rays_->uniform("clip_a"), n, a.data());
  gl_.Uniform3fv(rays_->uniform("clip_size"), n, size.data());
  gl_.UniformMatrix3fv(rays_->uniform("clip_rot"), n, GL_TRUE, rot.data());  // row-major
  gl_.Uniform3f(rays_->uniform("grid_origin"), float(clip.origin()[0]), float(clip.origin()[1]),
                float(clip.origin()[2]));
  gl_.Uniform3f(rays_->uniform("grid_spacing"), float(clip.spacing()[0]),
                float(clip.spacing()[1]), float(clip.spacing()[2]));
  if (surface_on_) {
    surface_tf_.set(*surface, quantized);
    gl_.Uniform2f(rays_->uniform("surface_map"), surface_tf_.scale(), surface_tf_.offset());
  }
}

void SliceCompositor::set_region(const PixelRect& r, const RenderSettings& settings) {
  region_ = {r.x0, r.y0, r.x1, r.y1};
  if (r.x1 <= r.x0 || r.y1 <= r.y0) {
    gl_.Disable(GL_SCISSOR_TEST);
    return;
  }
  gl_.Enable(GL_SCISSOR_TEST);
  gl_.Scissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
  clear(gl_, settings);
}

void SliceCompositor::begin_frame(const tsp::Camera& camera, const RenderSettings& settings,
                                  bool keep) {
  ctx_.make_current();
  // Without probes the caster samples in exact segments; pre-integration (the table read at
  // each segment's two ends), adaptive sampling and refinement have their own variants of it,
  // made on first use, as resolve_sampling reads the knobs.
  const bool plain = !clipping_;
  const SamplingMode mode = resolve_sampling(settings);
  adaptive_ = plain && mode == SamplingMode::adaptive;
  RayVariant v = clip_variant_;
  if (plain) switch (mode) {
      case SamplingMode::adaptive: v = RayVariant::adaptive; break;
      case SamplingMode::preintegrated: v = RayVariant::preintegrated; break;
      case SamplingMode::refined: v = RayVariant::refined; break;
      case SamplingMode::segments: v = RayVariant::segments; break;
    }
  rays_ = &ray_programs_.get(v);
  choose_backend(settings, plain);
  region_ = {};
  cpu_samples_ = 0;
  const tsp::CameraParams& params = camera.params();
  output_ = {settings.viewport_origin[0], settings.viewport_origin[1], params.width,
             params.height};
  target_.bind(params.width, params.height, settings.render_scale, keep);
  gl_.Disable(GL_SCISSOR_TEST);
  if (!keep) clear(gl_, settings);
  const FrameView view = frame_view(camera);
  draw_surface_under(camera, settings, view, keep);
  set_frame_uniforms(camera, settings, view, v == RayVariant::refined);
  if (cpu_) set_cast_scene(camera, settings, view, v == RayVariant::refined);
  gl_.ActiveTexture(GL_TEXTURE0 + kVolumeUnit);
  gl_.BeginQuery(GL_SAMPLES_PASSED, fragments_query_);
}

SliceCompositor::FrameView SliceCompositor::frame_view(const tsp::Camera& camera) {
  FrameView f;
  f.dir = camera.direction();
  f.eye = camera.eye();
  f.ray = camera.ray_direction();
  f.cosine = camera.ray_cosine();
  // The headlight: towards the viewer along the central ray, in world axes (the sample grid
  // stretched by the voxel size), where the shader takes the gradient too.
  // Voxel sizes normalised so the smallest is 1: the shader's gradients are per voxel.
  f.voxel = camera.params().voxel_size;
  const double smallest = std::min({f.voxel[0], f.voxel[1], f.voxel[2]});
  for (double& v : f.voxel) v /= smallest;
  f.light = {-f.ray[0] * f.voxel[0], -f.ray[1] * f.voxel[1], -f.ray[2] * f.voxel[2]};
  const double light_norm = std::hypot(f.light[0], f.light[1], f.light[2]);
  for (double& l : f.light) l /= light_norm;
  return f;
}

void SliceCompositor::draw_surface_under(const tsp::Camera& camera, const RenderSettings& settings,
                                         const FrameView& f, bool keep) {
  const tsp::CameraParams& view = camera.params();
  surface_drawn_ = false;
  surface_stats_ = {};
  if (settings.surface && has_surface() && settings.compositing == Compositing::rays) {
    // The opaque surface first, into its own target; its picture becomes the frame's
    // background and its depths end the rays (volume_ray.frag). Never kept: the frame is whole.
    assert(!keep);
    if (!surface_splats_) surface_splats_ = std::make_unique<SurfaceSplats>(ctx_);
    surface_stats_ = surface_splats_->draw(
        surface_, camera, clip_region_, target_.width(), target_.height(), settings.background,
        settings.shade, f.light, {1 / f.voxel[0], 1 / f.voxel[1], 1 / f.voxel[2]},
        {f.dir[0] / f.cosine, f.dir[1] / f.cosine, f.dir[2] / f.cosine});
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, target_.framebuffer());
    gl_.BlitFramebuffer(0, 0, target_.width(), target_.height(), 0, 0, target_.width(),
                        target_.height(), GL_COLOR_BUFFER_BIT, GL_NEAREST);
    target_.bind(view.width, view.height, settings.render_scale, keep);
    gl_.ActiveTexture(GL_TEXTURE0 + kSurfaceDepthUnit);
    gl_.BindTexture(GL_TEXTURE_2D, surface_splats_->depth_texture());
    surface_drawn_ = true;
  }
}

void SliceCompositor::set_frame_uniforms(const tsp::Camera& camera, const RenderSettings& settings,
                                         const FrameView& f, bool refine) {
  gl_.Disable(GL_DEPTH_TEST);
  gl_.Disable(GL_CULL_FACE);
  gl_.Enable(GL_BLEND);
  // Premultiplied colours composited back to front with "over"; alpha stays 1 (opaque image).
  gl_.BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  gl_.BindVertexArray(vao_);
  const glm::mat4 vp(camera.view_projection());
  for (const Program* p : std::initializer_list<const Program*>{&textured_, &flat_, &box_textured_, &box_flat_, rays_}) {
    p->use();
    gl_.UniformMatrix4fv(p->uniform("view_projection"), 1, GL_FALSE, glm::value_ptr(vp));
  }
  for (const Program* p : std::initializer_list<const Program*>{&box_textured_, &box_flat_, rays_}) {
    p->use();
    // Depth in the shaders is measured along direction() / ray_cosine(): along the central f.ray
    // it is f.ray length, so planes `spacing` apart in it take samples `spacing` apart along the
    // rays, and flat opacity accumulates per f.voxel of f.ray (the same for cubic voxels).
    gl_.Uniform3f(p->uniform("view_dir"), float(f.dir[0] / f.cosine), float(f.dir[1] / f.cosine),
                  float(f.dir[2] / f.cosine));
    gl_.Uniform3f(p->uniform("ray_dir"), float(f.ray[0]), float(f.ray[1]), float(f.ray[2]));
    gl_.Uniform3f(p->uniform("eye"), float(f.eye[0]), float(f.eye[1]), float(f.eye[2]));
    gl_.Uniform1i(p->uniform("perspective"), camera.perspective() ? 1 : 0);
  }
  for (const Program* p : std::initializer_list<const Program*>{&textured_, &box_textured_, rays_}) {
    p->use();
    gl_.Uniform2f(p->uniform("tf_map"), tf_.scale(), tf_.offset());
  }
  for (const Program* p : std::initializer_list<const Program*>{&box_textured_, rays_}) {
    p->use();
    gl_.Uniform1f(p->uniform("spacing"), float(settings.spacing));
  }
  for (const Program* p : std::initializer_list<const Program*>{&textured_, &box_textured_, rays_}) {
    p->use();
    gl_.Uniform1i(p->uniform("use_preintegrated"), settings.preintegrated ? 1 : 0);
    gl_.Uniform1i(p->uniform("use_stencil"), stencil_ ? 1 : 0);
    gl_.Uniform1i(p->uniform("use_shading"), settings.shade ? 1 : 0);
    gl_.Uniform4f(p->uniform("phong"), float(kAmbient), float(kDiffuse), float(kSpecular),
                  float(kSpecularPower));
    gl_.Uniform3f(p->uniform("light_dir"), float(f.light[0]), float(f.light[1]), float(f.light[2]));
    gl_.Uniform3f(p->uniform("inv_voxel"), float(1 / f.voxel[0]), float(1 / f.voxel[1]),
                  float(1 / f.voxel[2]));
  }
  // The back sample of a slice lies where the (central) f.ray meets the next plane, one spacing
  // along it.
  textured_.use();
  gl_.Uniform3f(textured_.uniform("back_step"), float(f.ray[0] * settings.spacing),
                float(f.ray[1] * settings.spacing), float(f.ray[2] * settings.spacing));
  if (settings.preintegrated) tf_.bind_preintegrated(kPreintegratedUnit, settings.spacing);
  if (surface_on_) surface_tf_.bind_opaque(kSurfaceTfUnit);
  tf_.bind(kTfUnit, settings.spacing);
  if (adaptive_) tf_.bind_rows(kTfRowsUnit, settings.spacing);
  if (refine)
    tf_.bind_refine(kRefineUnit, settings.spacing, tsp::kRefineSamples, settings.refine_tol);
  tf_.bind_levels(kLevelTfUnit, settings.spacing);  // (read by level pages with a row)
}

void SliceCompositor::set_cast_scene(const tsp::Camera& camera, const RenderSettings& settings,
                                     const FrameView& f, bool refine) {
  cast_.inverse_view_projection = glm::inverse(camera.view_projection());
  cast_.view_dir = glm::vec3(float(f.dir[0] / f.cosine), float(f.dir[1] / f.cosine), float(f.dir[2] / f.cosine));
  cast_.ray_dir = glm::vec3(float(f.ray[0]), float(f.ray[1]), float(f.ray[2]));
  cast_.eye = glm::vec3(float(f.eye[0]), float(f.eye[1]), float(f.eye[2]));
  cast_.perspective = camera.perspective();
  cast_.width = target_.width();
  cast_.height = target_.height();
  cast_.spacing = float(settings.spacing);
  cast_.stencil = stencil_;
  cast_.shade = settings.shade;
  cast_.phong = glm::vec4(float(kAmbient), float(kDiffuse), float(kSpecular), float(kSpecularPower));
  cast_.light_dir = glm::vec3(float(f.light[0]), float(f.light[1]), float(f.light[2]));
  cast_.inv_voxel = glm::vec3(float(1 / f.voxel[0]), float(1 / f.voxel[1]), float(1 / f.voxel[2]));
  cast_.tf.entries = tf_.size();
  cast_.tf.point = tf_.point_rgba().data();
  cast_.tf.refine = refine ? tf_.refine_rgba().data() : nullptr;
  cast_.tf.levels = tf_.levels_rgba().data();
  cast_.tf.scale = tf_.scale();
  cast_.tf.offset = tf_.offset();
}

void SliceCompositor::choose_backend(const RenderSettings& settings, bool plain) {
  const bool wanted = settings.backend == Backend::cpu ||
                      (settings.backend == Backend::automatic && software_gl_);
  std::string why;
  if (settings.compositing != Compositing::rays)
    why = std::string(to_string(settings.compositing)) + " compositing";
  else if (!plain)
    why = "clip probes";
  else if (adaptive_)
    why = "adaptive sampling (--sampling-tol)";
  else if (settings.preintegrated)
    why = "pre-integration";
  else if (settings.surface && has_surface())
    why = "a surface under the volume";
  cpu_ = wanted && why.empty();
  backend_note_ = wanted && !why.empty() ? "the cpu caster does not draw " + why + ": drawn by gl"
                                         : std::string();
}

void SliceCompositor::upload(const tsp::PolygonSoup& soup) {
  vertices_.assign(soup.xyz.begin(), soup.xyz.end());
  firsts_.resize(soup.size());
  counts_.resize(soup.size());
  GLint next = 0;
  for (std::size_t i = 0; i < soup.size(); ++i) {
    firsts_[i] = next;
    counts_[i] = GLsizei(soup.counts[i]);
    next += counts_[i];
  }
  gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices_.size() * sizeof(float)), vertices_.data(),
                 GL_STREAM_DRAW);
}

void SliceCompositor::draw(const std::vector<DrawItem>& items) {
  const Program* current = nullptr;
  bool boxes = false;  // cube vertex array bound, front faces culled
  auto use = [&](const Program& p, bool box) {
    if (&p != current) {
      p.use();
      current = &p;
    }
    if (box == boxes) return;
    boxes = box;
    gl_.BindVertexArray(box ? cube_vao_ : vao_);
    if (box) {
      gl_.Enable(GL_CULL_FACE);
      gl_.CullFace(GL_FRONT);  // back faces only: one fragment per pixel, eye inside or not
    } else {
      gl_.Disable(GL_CULL_FACE);
    }
  };
  auto texture_uniforms = [&](const Program& p, const DrawItem& it) {
    const BrickSlot& s = it.slot;
    gl_.BindTexture(GL_TEXTURE_3D, s.texture);
    // texture coordinate = (p·scale + offset)/atlas = (p − tex_origin)·tex_scale.
    gl_.Uniform3f(p.uniform("tex_origin"), -s.offset[0] / s.scale[0], -s.offset[1] / s.scale[1],
                  -s.offset[2] / s.scale[2]);
    gl_.Uniform3f(p.uniform("tex_scale"), s.scale[0] / float(s.atlas_size[0]),
                  s.scale[1] / float(s.atlas_size[1]), s.scale[2] / float(s.atlas_size[2]));
    float lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = (float(it.bounds.lo[a]) * s.scale[a] + s.offset[a]) / float(s.atlas_size[a]);
      hi[a] = (float(it.bounds.hi[a]) * s.scale[a] + s.offset[a]) / float(s.atlas_size[a]);
    }
    gl_.Uniform3f(p.uniform("tex_lo"), lo[0], lo[1], lo[2]);
    gl_.Uniform3f(p.uniform("tex_hi"), hi[0], hi[1], hi[2]);
  };
  for (const DrawItem& it : items) {
    if (it.as_box) {
      const Program& p = it.slot.texture ? box_textured_ : box_flat_;
      use(p, true);
      const auto& b = it.bounds;
      gl_.Uniform3f(p.uniform("box_lo"), float(b.lo[0]), float(b.lo[1]), float(b.lo[2]));
      gl_.Uniform3f(p.uniform("box_hi"), float(b.hi[0]), float(b.hi[1]), float(b.hi[2]));
      if (it.slot.texture) {
        texture_uniforms(p, it);
      } else {
        gl_.Uniform3f(p.uniform("flat_rgb"), it.flat.r, it.flat.g, it.flat.b);
        gl_.Uniform1f(p.uniform("log_transmittance"), log_transmittance(it.flat.a));
      }
      gl_.DrawArrays(GL_TRIANGLES, 0, kCubeVertices);
      continue;
    }
    if (it.polygon_count == 0) continue;
    const Program& p = it.slot.texture ? textured_ : flat_;
    use(p, false);
    if (it.slot.texture)
      texture_uniforms(p, it);
    else
      gl_.Uniform4fv(flat_.uniform("flat_colour"), 1, it.colour.data());
    gl_.MultiDrawArrays(GL_TRIANGLE_FAN, firsts_.data() + it.first_polygon,
                        counts_.data() + it.first_polygon, it.polygon_count);
  }
  if (boxes) {
    gl_.Disable(GL_CULL_FACE);
    gl_.BindVertexArray(vao_);
  }
}

void SliceCompositor::set_pages(const BrickPages& pages, tsp::Dims dims, const tsp::Aabb* bounds) {
  const auto& g = pages.grid();
  gl_.ActiveTexture(GL_TEXTURE0 + kPagesUnit);
  gl_.BindTexture(GL_TEXTURE_3D, pages_);
  gl_.TexImage3D(GL_TEXTURE_3D, 0, GL_RGBA32F, g[0], g[1], g[2], 0, GL_RGBA, GL_FLOAT,
                 pages.texels().data());
  gl_.ActiveTexture(GL_TEXTURE0 + kVolumeUnit);
  const BrickSlot& atlas = pages.atlas();
  rays_atlas_ = atlas.texture;
  rays_->use();
  gl_.Uniform3f(rays_->uniform("atlas_scale"), atlas.texture ? 1.f / float(atlas.atlas_size[0]) : 0.f,
                atlas.texture ? 1.f / float(atlas.atlas_size[1]) : 0.f,
                atlas.texture ? 1.f / float(atlas.atlas_size[2]) : 0.f);
  const auto& c = pages.cell();
  gl_.Uniform3f(rays_->uniform("cell"), float(c[0]), float(c[1]), float(c[2]));
  gl_.Uniform3i(rays_->uniform("grid"), g[0], g[1], g[2]);
  tsp::Aabb box{{0, 0, 0},
                {double(std::max(dims.x - 1, 1)), double(std::max(dims.y - 1, 1)),
                 double(std::max(dims.z - 1, 1))}};
  if (bounds) box = *bounds;
  gl_.Uniform3f(rays_->uniform("box_lo"), float(box.lo[0]), float(box.lo[1]), float(box.lo[2]));
  gl_.Uniform3f(rays_->uniform("box_hi"), float(box.hi[0]), float(box.hi[1]), float(box.hi[2]));
  cast_.grid = g;
  cast_.cell = c;
  cast_.pages = pages.texels().data();
  cast_.volume = atlas.host;
  cast_.runs = pages.runs();
  assert((!cpu_ || !atlas.texture || atlas.host) && "a CPU frame's textures need their texels in RAM");
  cast_.box_lo = glm::vec3(float(box.lo[0]), float(box.lo[1]), float(box.lo[2]));
  cast_.box_hi = glm::vec3(float(box.hi[0]), float(box.hi[1]), float(box.hi[2]));
}

void SliceCompositor::set_step_map(const std::vector<std::uint8_t>& rows, std::array<int, 3> grid,
                                   std::array<int, 3> cell) {
  if (!adaptive_) return;
  assert(rows.size() == std::size_t(grid[0]) * grid[1] * grid[2]);
  const float count = float(tsp::kStepMultipliers.size());
  step_texels_.clear();
  for (std::uint8_t r : rows)
    step_texels_.insert(step_texels_.end(),
                        {float(tsp::kStepMultipliers[r]), (float(r) + 0.5f) / count});
  gl_.ActiveTexture(GL_TEXTURE0 + kStepMapUnit);
  gl_.BindTexture(GL_TEXTURE_3D, step_map_);
  gl_.TexImage3D(GL_TEXTURE_3D, 0, GL_RG32F, grid[0], grid[1], grid[2], 0, GL_RG, GL_FLOAT,
                 step_texels_.data());
  gl_.ActiveTexture(GL_TEXTURE0 + kVolumeUnit);
  rays_->use();
  // Sample point p (voxel units) lies in brick floor(p / cell): coordinate p / (grid · cell).
  gl_.Uniform3f(rays_->uniform("step_scale"), 1.f / float(grid[0] * cell[0]),
                1.f / float(grid[1] * cell[1]), 1.f / float(grid[2] * cell[2]));
}

void SliceCompositor::draw_rays() {
  // A mesh's boundary is closed and the volume lies inside it: drawn opaque and whole (no
  // probe cuts it open), it hides every ray's samples.
  if (surface_drawn_ && !clip_region_.active()) return;
  if (cpu_) {
    if (!cpu_pass_) cpu_pass_ = std::make_unique<CpuPass>(gl_);
    cpu_samples_ += cpu_pass_->draw(cast_, region_).samples;
    return;
  }
  gl_.BindTexture(GL_TEXTURE_3D, rays_atlas_);
  rays_->use();
  gl_.Uniform1i(rays_->uniform("use_surface_depth"), surface_drawn_ ? 1 : 0);
  gl_.BindVertexArray(cube_vao_);
  gl_.Enable(GL_CULL_FACE);
  gl_.CullFace(GL_FRONT);
  gl_.DrawArrays(GL_TRIANGLES, 0, kCubeVertices);
  gl_.Disable(GL_CULL_FACE);
  gl_.BindVertexArray(vao_);
}

std::int64_t SliceCompositor::end_frame() {
  gl_.EndQuery(GL_SAMPLES_PASSED);
  gl_.Disable(GL_SCISSOR_TEST);
  target_.resolve(output_[0], output_[1], output_[2], output_[3]);
  ctx_.finish();
  GLuint64 fragments = 0;
  gl_.GetQueryObjectui64v(fragments_query_, GL_QUERY_RESULT, &fragments);
  return std::int64_t(fragments);
}

}  // namespace tspgl

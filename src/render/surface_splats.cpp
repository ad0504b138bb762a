#include "render/surface_splats.h"

#include <cassert>
#include <cstdint>

#include <glm/gtc/type_ptr.hpp>

#include "gl/gl_error.h"
#include "gl/gl_objects.h"
#include "render/render_settings.h"
#include "tsp/core/stopwatch.h"

namespace tspgl {

namespace {
constexpr int kSplatTfUnit = 0;
constexpr int kFloatsPerSplat = 18;  // centre, normal, radius, value, leaf, 3 corners
constexpr float kNoDepth = 1e30f;  // the depth target where no splat is drawn
}  // namespace

SurfaceSplats::SurfaceSplats(GlContext& ctx)
    : ctx_(ctx), gl_(ctx.gl()), program_(load_program(gl_, "surface_splat.vert", "surface_splat.frag")),
      tf_(gl_) {
  gl_.GenVertexArrays(1, &vao_);
  gl_.GenBuffers(1, &vbo_);
  gl_.BindVertexArray(vao_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  const GLsizei stride = kFloatsPerSplat * sizeof(float);
  const int offsets[6] = {0, 3, 6, 9, 12, 15}, sizes[6] = {3, 3, 3, 3, 3, 3};
  for (GLuint a = 0; a < 6; ++a) {
    gl_.EnableVertexAttribArray(a);
    gl_.VertexAttribPointer(a, sizes[a], GL_FLOAT, GL_FALSE, stride,
                            reinterpret_cast<const void*>(std::uintptr_t(offsets[a] * sizeof(float))));
    gl_.VertexAttribDivisor(a, 1);  // per splat
  }
  gl_.BindVertexArray(0);
  program_.use();
  gl_.Uniform1i(program_.uniform("splat_tf"), kSplatTfUnit);
  check_gl(gl_, "setting up the surface splats");
}

SurfaceSplats::~SurfaceSplats() {
  gl_.DeleteBuffers(1, &vbo_);
  gl_.DeleteVertexArrays(1, &vao_);
  if (fbo_) gl_.DeleteFramebuffers(1, &fbo_);
  if (colour_) gl_.DeleteRenderbuffers(1, &colour_);
  if (depth_rb_) gl_.DeleteRenderbuffers(1, &depth_rb_);
  if (depth_tex_) gl_.DeleteTextures(1, &depth_tex_);
}

void SurfaceSplats::resize(int width, int height) {
  if (fbo_ && width == width_ && height == height_) return;
  if (!fbo_) {
    gl_.GenFramebuffers(1, &fbo_);
    gl_.GenRenderbuffers(1, &colour_);
    gl_.GenRenderbuffers(1, &depth_rb_);
    gl_.GenTextures(1, &depth_tex_);
  }
  gl_.BindTexture(GL_TEXTURE_2D, depth_tex_);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_R32F, width, height, 0, GL_RED, GL_FLOAT, nullptr);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  attach_renderbuffer(gl_, GL_COLOR_ATTACHMENT0, colour_, GL_RGBA16, width, height);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, depth_tex_, 0);
  attach_renderbuffer(gl_, GL_DEPTH_ATTACHMENT, depth_rb_, GL_DEPTH_COMPONENT24, width, height);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw tsp::GlError("the surface target (RGBA16 + R32F + depth framebuffer) is not supported");
  width_ = width;
  height_ = height;
}

SurfaceStats SurfaceSplats::draw(const SurfaceFrame& s, const tsp::Camera& camera,
                                 const tsp::ClipRegion& clip, int width, int height,
                                 const std::array<float, 3>& background, bool shade,
                                 const std::array<double, 3>& light,
                                 const std::array<double, 3>& inv_voxel,
                                 const std::array<double, 3>& view_dir) {
  assert(s.tree && s.tf);
  SurfaceStats stats;
  tsp::Stopwatch watch;
  instances_.clear();
  for (int id : tsp::splat_surface_cut(*s.tree, camera, s.min_px)) {
    const tsp::SplatTreeNode& node = s.tree->nodes[std::size_t(id)];
    const tsp::SurfaceSplat& p = node.splat;
    if (clip.active() && !clip.kept({p.centre[0], p.centre[1], p.centre[2]})) continue;
    instances_.insert(instances_.end(), {p.centre[0], p.centre[1], p.centre[2], p.normal[0],
                                         p.normal[1], p.normal[2], p.radius, p.value,
                                         node.is_leaf() ? 1.f : 0.f});
    for (const auto& c : node.triangle) instances_.insert(instances_.end(), c.begin(), c.end());
  }
  stats.splats = int(instances_.size() / kFloatsPerSplat);
  stats.cut_ms = watch.ms();

  resize(width, height);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.Viewport(0, 0, width, height);
  gl_.Disable(GL_SCISSOR_TEST);
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  // Cleared one attachment at a time: the picture to the background, the depths to none.
  gl_.DrawBuffers(1, &both[1]);
  gl_.ClearColor(kNoDepth, 0, 0, 0);
  gl_.Clear(GL_COLOR_BUFFER_BIT);
  gl_.DrawBuffers(1, &both[0]);
  gl_.ClearColor(background[0], background[1], background[2], 1.f);
  gl_.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl_.DrawBuffers(2, both);
  if (stats.splats > 0) {
    if (s.tf != tf_source_ || s.tf->version() != tf_version_) {
      // The value itself is the "code": tf coordinate = (v − domain.lo) / domain.width.
      tf_.set(*s.tf, {0, 1});
      tf_source_ = s.tf;
      tf_version_ = s.tf->version();
    }
    tf_.bind_opaque(kSplatTfUnit);
    program_.use();
    const glm::mat4 vp(camera.view_projection());
    gl_.UniformMatrix4fv(program_.uniform("view_projection"), 1, GL_FALSE, glm::value_ptr(vp));
    gl_.Uniform3f(program_.uniform("view_dir"), float(view_dir[0]), float(view_dir[1]), float(view_dir[2]));
    gl_.Uniform2f(program_.uniform("splat_map"), tf_.scale(), tf_.offset());
    gl_.Uniform1i(program_.uniform("use_shading"), shade ? 1 : 0);
    gl_.Uniform4f(program_.uniform("phong"), float(kAmbient), float(kDiffuse), float(kSpecular),
                  float(kSpecularPower));
    gl_.Uniform3f(program_.uniform("light_dir"), float(light[0]), float(light[1]), float(light[2]));
    gl_.Uniform3f(program_.uniform("inv_voxel"), float(inv_voxel[0]), float(inv_voxel[1]),
                  float(inv_voxel[2]));
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(GL_LESS);
    gl_.DepthMask(GL_TRUE);
    gl_.Disable(GL_BLEND);
    gl_.Disable(GL_CULL_FACE);
    gl_.BindVertexArray(vao_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
    gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(instances_.size() * sizeof(float)), instances_.data(),
                   GL_STREAM_DRAW);
    gl_.DrawArraysInstanced(GL_TRIANGLES, 0, 6, stats.splats);
    gl_.BindVertexArray(0);
    gl_.Disable(GL_DEPTH_TEST);
  }
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
  check_gl(gl_, "drawing the surface splats");
  ctx_.finish();  // timed on its own (what --surface-target-ms holds)
  stats.ms = watch.ms();
  return stats;
}

}  // namespace tspgl

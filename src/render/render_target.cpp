#include "render/render_target.h"

#include <algorithm>
#include <cmath>

#include "gl/gl_error.h"

namespace tspgl {

RenderTarget::~RenderTarget() {
  if (fbo_) gl_.DeleteFramebuffers(1, &fbo_);
  if (colour_) gl_.DeleteRenderbuffers(1, &colour_);
  if (held_fbo_) gl_.DeleteFramebuffers(1, &held_fbo_);
  if (held_colour_) gl_.DeleteRenderbuffers(1, &held_colour_);
}

void RenderTarget::bind(int width, int height, double scale, bool keep) {
  const int w = std::max(1, int(std::lround(width * scale)));
  const int h = std::max(1, int(std::lround(height * scale)));
  if (!fbo_ || width_ != w || height_ != h) {
    // Keeping the picture: the old buffers are read into the new ones, then deleted.
    GLuint old_fbo = 0, old_colour = 0;
    if (keep && fbo_) {
      old_fbo = fbo_;
      old_colour = colour_;
      fbo_ = colour_ = 0;
    }
    if (!fbo_) gl_.GenFramebuffers(1, &fbo_);
    if (!colour_) gl_.GenRenderbuffers(1, &colour_);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, colour_);
    // RGBA16 (unorm) blends fastest on llvmpipe of RGBA16/16F/32F and keeps 16 bits.
    gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA16, w, h);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
    if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw tsp::GlError("the 16-bit render target (RGBA16 framebuffer) is not supported");
    if (old_fbo) {
      gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, old_fbo);
      gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_);
      gl_.BlitFramebuffer(0, 0, width_, height_, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_LINEAR);
      gl_.DeleteFramebuffers(1, &old_fbo);
      gl_.DeleteRenderbuffers(1, &old_colour);
    }
    width_ = w;
    height_ = h;
  }
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.Viewport(0, 0, width_, height_);
}

void RenderTarget::hold() {
  if (!fbo_) return;
  if (!held_fbo_ || held_width_ != width_ || held_height_ != height_) {
    if (!held_fbo_) gl_.GenFramebuffers(1, &held_fbo_);
    if (!held_colour_) gl_.GenRenderbuffers(1, &held_colour_);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, held_colour_);
    gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA16, width_, height_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, held_fbo_);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                held_colour_);
    if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw tsp::GlError("the held copy of the render target (RGBA16) is not supported");
    held_width_ = width_;
    held_height_ = height_;
  }
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, held_fbo_);
  gl_.BlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
}

bool RenderTarget::restore_held() {
  if (!held_fbo_ || held_width_ < 1) return false;
  bind(held_width_, held_height_);
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, held_fbo_);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_);
  gl_.BlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  return true;
}

void RenderTarget::resolve(int x, int y, int w, int h) {
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, ctx_.canvas_framebuffer());
  const bool same = width_ == w && height_ == h;
  gl_.BlitFramebuffer(0, 0, width_, height_, x, y, x + w, y + h, GL_COLOR_BUFFER_BIT,
                      same ? GL_NEAREST : GL_LINEAR);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, ctx_.canvas_framebuffer());
}

}  // namespace tspgl

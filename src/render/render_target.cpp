#include "render/render_target.h"

#include "gl/gl_error.h"

namespace tspgl {

RenderTarget::~RenderTarget() {
  if (fbo_) gl_.DeleteFramebuffers(1, &fbo_);
  if (colour_) gl_.DeleteRenderbuffers(1, &colour_);
}

void RenderTarget::bind() {
  if (!fbo_ || width_ != ctx_.width() || height_ != ctx_.height()) {
    if (!fbo_) gl_.GenFramebuffers(1, &fbo_);
    if (!colour_) gl_.GenRenderbuffers(1, &colour_);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, colour_);
    // RGBA16 (unorm) blends fastest on llvmpipe of RGBA16/16F/32F and keeps 16 bits.
    gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA16, ctx_.width(), ctx_.height());
    gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
    if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw tsp::GlError("the 16-bit render target (RGBA16 framebuffer) is not supported");
    width_ = ctx_.width();
    height_ = ctx_.height();
  }
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.Viewport(0, 0, width_, height_);
}

void RenderTarget::resolve() {
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  gl_.BlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace tspgl

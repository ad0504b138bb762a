#include "gl/offscreen_canvas.h"

#include <string>

#include "gl/gl_error.h"
#include "gl/gl_objects.h"
#include "tsp/core/error.h"

namespace tspgl {

OffscreenCanvas::OffscreenCanvas(GlContext& ctx, int width, int height)
    : ctx_(ctx), width_(width), height_(height) {
  const GlApi& gl = ctx_.gl();
  GLint max_size = 0;
  gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    throw tsp::UsageError("offscreen canvas " + std::to_string(width) + "x" +
                          std::to_string(height) + ": expected each side in [1, " +
                          std::to_string(max_size) + "]");
  GLint previous = 0;
  gl.GetIntegerv(GL_FRAMEBUFFER_BINDING, &previous);
  gl.GenFramebuffers(1, &fbo_);
  gl.GenRenderbuffers(1, &colour_);
  gl.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  attach_renderbuffer(gl, GL_COLOR_ATTACHMENT0, colour_, GL_RGBA8, width, height);
  const bool complete = gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  gl.BindFramebuffer(GL_FRAMEBUFFER, GLuint(previous));
  if (!complete) {
    gl.DeleteFramebuffers(1, &fbo_);
    gl.DeleteRenderbuffers(1, &colour_);
    throw tsp::GlError("the offscreen canvas (RGBA8 framebuffer) is not supported");
  }
  check_gl(gl, "offscreen canvas");
}

OffscreenCanvas::~OffscreenCanvas() {
  const GlApi& gl = ctx_.gl();
  gl.DeleteFramebuffers(1, &fbo_);
  gl.DeleteRenderbuffers(1, &colour_);
}

CanvasScope::CanvasScope(OffscreenCanvas& canvas)
    : ctx_(canvas.context()), previous_(ctx_.canvas_) {
  ctx_.canvas_ = {canvas.framebuffer(), canvas.width(), canvas.height()};
  ctx_.gl().BindFramebuffer(GL_FRAMEBUFFER, canvas.framebuffer());
}

CanvasScope::~CanvasScope() {
  ctx_.canvas_ = previous_;
  ctx_.gl().BindFramebuffer(GL_FRAMEBUFFER, previous_.fbo);
}

}  // namespace tspgl

// An offscreen canvas in a context the caller already has: an RGBA8 framebuffer that stands in
// for the context's default framebuffer while a CanvasScope is open. The bench's and --quality's
// probes render their pictures this way — in the player, in the window's own context, so the
// window's context stays current and keeps drawing (never another context made current on the
// UI thread).
#pragma once
#include "gl/context.h"

namespace tspgl {

/// An RGBA8 framebuffer of a fixed size in one context. Use from the context's thread with the
/// context current; not copyable.
class OffscreenCanvas {
 public:
  /// Allocates it in ctx (which must be current and outlive it). Throws tsp::UsageError for a
  /// size outside [1, GL_MAX_RENDERBUFFER_SIZE], tsp::GlError when GL cannot make it.
  OffscreenCanvas(GlContext& ctx, int width, int height);
  /// Deletes the framebuffer (the context must be current; no CanvasScope may be open on it).
  ~OffscreenCanvas();
  OffscreenCanvas(const OffscreenCanvas&) = delete;
  OffscreenCanvas& operator=(const OffscreenCanvas&) = delete;

  /// The context it lives in.
  GlContext& context() const { return ctx_; }
  /// Its width in pixels.
  int width() const { return width_; }
  /// Its height in pixels.
  int height() const { return height_; }
  /// Its framebuffer object.
  GLuint framebuffer() const { return fbo_; }

 private:
  GlContext& ctx_;
  GLuint fbo_ = 0, colour_ = 0;
  int width_ = 0, height_ = 0;
};

/// While it lives, the canvas is its context's canvas: renderers resolve their frames into it
/// and GlContext::read_pixels reads it. Scopes nest; the destructor restores the canvas before
/// it and binds it. Use from the context's thread; not copyable.
class CanvasScope {
 public:
  /// Makes canvas its context's canvas. Never throws.
  explicit CanvasScope(OffscreenCanvas& canvas);
  /// Restores the previous canvas. Never throws.
  ~CanvasScope();
  CanvasScope(const CanvasScope&) = delete;
  CanvasScope& operator=(const CanvasScope&) = delete;

 private:
  GlContext& ctx_;
  GlContext::Canvas previous_;
};

}  // namespace tspgl

// The 16-bit colour buffer frames are composited in: in 8 bits each thin slice's premultiplied
// contribution (a few 1/255 steps) is rounded, and over hundreds of slices the error reaches
// ΔE 10 (tests/render: the constant cube). Blitted to the default framebuffer once per frame.
#pragma once
#include "gl/context.h"

namespace tspgl {

/// An RGBA16 framebuffer the size of a frame (the camera's), copied into a rectangle of a
/// context's canvas (its default framebuffer, or an
/// OffscreenCanvas in use). Use from the context's thread with the context current; not
/// copyable.
class RenderTarget {
 public:
  /// Nothing is allocated until bind().
  explicit RenderTarget(GlContext& ctx) : ctx_(ctx), gl_(ctx.gl()) {}
  /// Deletes the framebuffer (the context must be current).
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;

  /// (Re)allocates it at width × height times scale (in (0, 1]; at least 1 pixel) when needed,
  /// binds it and sets the viewport. With keep, a reallocation copies the old picture into the
  /// new size (magnified with linear filtering, as resolve() showed it). Throws tsp::GlError
  /// when RGBA16 framebuffers are not supported.
  void bind(int width, int height, double scale = 1, bool keep = false);
  /// Copies it into the rectangle of the context's canvas whose lower-left corner is (x, y) and
  /// whose size is w × h (magnified with linear filtering when it differs) and binds the canvas.
  void resolve(int x, int y, int w, int h);
  /// Copies the picture into a second buffer of its size (replacing what was held), so a later
  /// restore_held() can bring it back (the player's Space: the picture on screen as it went
  /// down, when the frame drawing the next step is dropped). Throws tsp::GlError.
  void hold();
  /// Makes the held picture the target's again (at the held size) and binds the target; false
  /// (nothing changed) when nothing is held. Never throws but tsp::GlError.
  bool restore_held();
  /// The framebuffer (0 before the first bind()).
  GLuint framebuffer() const { return fbo_; }
  /// Its size in pixels (after the scale), as last bound.
  int width() const { return width_; }
  /// See width().
  int height() const { return height_; }

 private:
  GlContext& ctx_;
  const GlApi& gl_;
  GLuint fbo_ = 0, colour_ = 0;
  int width_ = 0, height_ = 0;
  GLuint held_fbo_ = 0, held_colour_ = 0;  // hold()'s copy
  int held_width_ = 0, held_height_ = 0;   // its size (0: nothing held)
};

}  // namespace tspgl

// OffscreenCanvas / CanvasScope: while a scope is open the canvas is the context's canvas —
// a RenderTarget resolves into it and read_pixels reads it — and the default framebuffer is left
// as it was; scopes nest and restore what was there before.
#include <gtest/gtest.h>

#include "gl/context.h"
#include "gl/offscreen_canvas.h"
#include "render/render_target.h"
#include "tsp/core/error.h"

namespace {

using tspgl::GlApi;

void clear(const GlApi& gl, float r, float g, float b) {
  gl.ClearColor(r, g, b, 1);
  gl.Clear(GL_COLOR_BUFFER_BIT);
}

// Every pixel of im is (r, g, b, 255).
void expect_all(const tsp::Image& im, int r, int g, int b) {
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const std::uint8_t* p = im.at(x, y);
      ASSERT_EQ(p[0], r) << x << "," << y;
      ASSERT_EQ(p[1], g) << x << "," << y;
      ASSERT_EQ(p[2], b) << x << "," << y;
    }
}

TEST(OffscreenCanvas, FramesResolveIntoItAndTheDefaultFramebufferIsLeftAlone) {
  auto ctx = tspgl::create_offscreen_context(8, 6);
  const GlApi& gl = ctx->gl();
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl.Viewport(0, 0, 8, 6);
  clear(gl, 1, 0, 0);  // the default framebuffer: red
  tspgl::OffscreenCanvas canvas(*ctx, 5, 4);
  {
    const tspgl::CanvasScope scope(canvas);
    EXPECT_EQ(ctx->canvas_framebuffer(), canvas.framebuffer());
    EXPECT_EQ(ctx->canvas_width(), 5);
    EXPECT_EQ(ctx->canvas_height(), 4);
    tspgl::RenderTarget target(*ctx);
    target.bind(5, 4);
    clear(gl, 0, 1, 0);  // a frame: green
    target.resolve(0, 0, 5, 4);
    const tsp::Image in_canvas = ctx->read_pixels();
    ASSERT_EQ(in_canvas.width, 5);
    ASSERT_EQ(in_canvas.height, 4);
    expect_all(in_canvas, 0, 255, 0);
  }
  EXPECT_EQ(ctx->canvas_framebuffer(), 0u);
  const tsp::Image shown = ctx->read_pixels();
  ASSERT_EQ(shown.width, 8);
  ASSERT_EQ(shown.height, 6);
  expect_all(shown, 255, 0, 0);
  GLint bound = -1;
  gl.GetIntegerv(GL_FRAMEBUFFER_BINDING, &bound);
  EXPECT_EQ(bound, 0);
}

TEST(OffscreenCanvas, ScopesNestAndRestoreTheCanvasBefore) {
  auto ctx = tspgl::create_offscreen_context(4, 4);
  const GlApi& gl = ctx->gl();
  tspgl::OffscreenCanvas outer(*ctx, 3, 3), inner(*ctx, 2, 2);
  const tspgl::CanvasScope a(outer);
  gl.Viewport(0, 0, 3, 3);
  clear(gl, 0, 0, 1);
  {
    const tspgl::CanvasScope b(inner);
    gl.Viewport(0, 0, 2, 2);
    clear(gl, 1, 1, 1);
    expect_all(ctx->read_pixels(), 255, 255, 255);
  }
  EXPECT_EQ(ctx->canvas_framebuffer(), outer.framebuffer());
  const tsp::Image im = ctx->read_pixels();
  ASSERT_EQ(im.width, 3);
  expect_all(im, 0, 0, 255);
}

TEST(OffscreenCanvas, RefusesAnEmptySize) {
  auto ctx = tspgl::create_offscreen_context(4, 4);
  EXPECT_THROW(tspgl::OffscreenCanvas(*ctx, 0, 4), tsp::UsageError);
  EXPECT_THROW(tspgl::OffscreenCanvas(*ctx, 4, -1), tsp::UsageError);
}

}  // namespace

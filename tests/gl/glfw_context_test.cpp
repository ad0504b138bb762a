#include <gtest/gtest.h>

#include <cstdlib>

#include "gl/context.h"
#include "gl/gl_error.h"
#include "gl/shader.h"
#include "support/paths.h"

namespace {

bool have_display() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x11 && *x11) || (wayland && *wayland);
}

constexpr int kW = 96, kH = 64;

TEST(GlfwContext, HiddenWindowGivesA33CoreContextThatClearsAndReadsBack) {
  TSPTEST_REQUIRE(have_display(), "no DISPLAY/WAYLAND_DISPLAY (run under xvfb-run)");
  auto ctx = tspgl::create_window_context(kW, kH, "tspplay test", false);
  EXPECT_EQ(ctx->width(), kW);
  EXPECT_EQ(ctx->height(), kH);
  EXPECT_NE(ctx->native_window(), nullptr);
  EXPECT_FALSE(ctx->should_close());
  const tspgl::GlApi& gl = ctx->gl();
  GLint profile = 0;
  gl.GetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  gl.Viewport(0, 0, ctx->width(), ctx->height());
  gl.ClearColor(0.2f, 0.4f, 0.6f, 1.0f);
  gl.Clear(GL_COLOR_BUFFER_BIT);
  ctx->finish();
  const tsp::Image img = ctx->read_pixels();
  ASSERT_EQ(img.width, kW);
  ASSERT_EQ(img.height, kH);
  for (int y : {0, kH / 2, kH - 1})
    for (int x : {0, kW / 2, kW - 1}) {
      const std::uint8_t* p = img.at(x, y);
      EXPECT_EQ(p[0], 51);
      EXPECT_EQ(p[1], 102);
      EXPECT_EQ(p[2], 153);
    }
  // The embedded shaders compile on this driver too.
  EXPECT_NE(tspgl::load_program(gl, "solid2d.vert", "solid.frag").id(), 0u);
  ctx->swap_buffers();
  ctx->poll_events();
}

TEST(GlfwContext, TwoWindowsInTurnReinitialiseGlfw) {
  TSPTEST_REQUIRE(have_display(), "no DISPLAY/WAYLAND_DISPLAY (run under xvfb-run)");
  for (int k = 0; k < 2; ++k) {
    auto ctx = tspgl::create_window_context(16, 16, "tspplay test", false);
    ctx->make_current();
    tspgl::check_gl(ctx->gl(), "window " + std::to_string(k));
  }
}

TEST(GlfwContext, InvalidSizeIsAUsageError) {
  EXPECT_THROW(tspgl::create_window_context(0, 10, "x", false), tsp::UsageError);
}

TEST(GlfwContext, NoDisplayIsAGlError) {
  if (have_display()) GTEST_SKIP() << "a display is available";
  EXPECT_THROW(tspgl::create_window_context(16, 16, "x", false), tsp::GlError);
}

}  // namespace

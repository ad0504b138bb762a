#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "gl/context.h"
#include "gl/gl_error.h"
#include "gl/gl_objects.h"
#include "gl/shader.h"
#include "support/paths.h"

namespace {

using tspgl::GlApi;

constexpr int kW = 64, kH = 48;

// The clear colour as exactly representable 8-bit values (k/255).
constexpr std::uint8_t kClear[4] = {51, 102, 153, 204};

std::string error_text(const std::function<void()>& f) {
  try {
    f();
  } catch (const tsp::GlError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no tsp::GlError";
  return "";
}

// Draws the triangle strip of `corners` (clip-space x, y pairs) in colour rgba with the
// embedded solid2d.vert + solid.frag program.
void draw_solid(const GlApi& gl, const std::vector<float>& corners, const float rgba[4]) {
  tspgl::Program p = tspgl::load_program(gl, "solid2d.vert", "solid.frag");
  GLuint vao = 0, vbo = 0;
  tspgl::make_vertex_array(gl, vao, vbo, 2, corners);
  p.use();
  const GLint loc = p.uniform("u_color");
  ASSERT_GE(loc, 0);
  gl.Uniform4f(loc, rgba[0], rgba[1], rgba[2], rgba[3]);
  gl.DrawArrays(GL_TRIANGLE_STRIP, 0, GLsizei(corners.size() / 2));
  gl.DeleteBuffers(1, &vbo);
  gl.DeleteVertexArrays(1, &vao);
  tspgl::check_gl(gl, "draw_solid");
}

// A kW × kH context whose viewport is the whole image, cleared to (r, g, b, a).
std::unique_ptr<tspgl::GlContext> cleared_context(float r, float g, float b, float a) {
  auto ctx = tspgl::create_offscreen_context(kW, kH);
  const GlApi& gl = ctx->gl();
  gl.Viewport(0, 0, kW, kH);
  gl.ClearColor(r, g, b, a);
  gl.Clear(GL_COLOR_BUFFER_BIT);
  return ctx;
}

// How many pixels of img are not exactly rgba.
int pixels_other_than(const tsp::Image& img, const std::uint8_t (&rgba)[4]) {
  int bad = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 4; ++c) bad += img.at(x, y)[c] != rgba[c];
  return bad;
}

TEST(OsmesaContext, IsA33CoreContextOfTheRequestedSize) {
  auto ctx = tspgl::create_offscreen_context(kW, kH);
  EXPECT_EQ(ctx->width(), kW);
  EXPECT_EQ(ctx->height(), kH);
  const GlApi& gl = ctx->gl();
  GLint major = 0, minor = 0, profile = 0;
  gl.GetIntegerv(GL_MAJOR_VERSION, &major);
  gl.GetIntegerv(GL_MINOR_VERSION, &minor);
  gl.GetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_GE(major * 10 + minor, 33);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_NE(ctx->describe().find("OpenGL"), std::string::npos);
  EXPECT_FALSE(ctx->should_close());
  EXPECT_EQ(ctx->native_window(), nullptr);
  // The context's own get-proc-address resolves core entry points (for other loaders).
  EXPECT_NE(ctx->proc_address_function()("glTexImage3D"), nullptr);
}

TEST(OsmesaContext, ClearColourReadsBackExactlyEverywhere) {
  auto ctx = cleared_context(kClear[0] / 255.0f, kClear[1] / 255.0f, kClear[2] / 255.0f,
                             kClear[3] / 255.0f);
  ctx->finish();
  const tsp::Image img = ctx->read_pixels();
  ASSERT_EQ(img.width, kW);
  ASSERT_EQ(img.height, kH);
  EXPECT_EQ(pixels_other_than(img, kClear), 0);
}

TEST(OsmesaContext, FullScreenTriangleInAUniformColour) {
  auto ctx = cleared_context(0, 0, 0, 0);
  // One triangle whose interior contains the whole [-1, 1]² clip square.
  const float colour[4] = {1.0f, 128 / 255.0f, 0.0f, 1.0f};
  draw_solid(ctx->gl(), {-1, -1, 3, -1, -1, 3}, colour);
  EXPECT_EQ(pixels_other_than(ctx->read_pixels(), {255, 128, 0, 255}), 0);
}

TEST(OsmesaContext, ReadPixelsReturnsTheTopRowFirst) {
  auto ctx = cleared_context(0, 0, 1, 1);
  // A red quad over the upper half of clip space (y > 0) = the top kH/2 rows of the image.
  const float red[4] = {1, 0, 0, 1};
  draw_solid(ctx->gl(), {-1, 0, 1, 0, -1, 1, 1, 1}, red);
  const tsp::Image img = ctx->read_pixels();
  for (int y = 0; y < kH; ++y) {
    const bool top = y < kH / 2;
    for (int x = 0; x < kW; ++x) {
      const std::uint8_t* p = img.at(x, y);
      ASSERT_EQ(p[0], top ? 255 : 0) << x << "," << y;
      ASSERT_EQ(p[2], top ? 0 : 255) << x << "," << y;
    }
  }
}

TEST(OsmesaContext, ShaderCompileErrorCarriesTheInfoLog) {
  auto ctx = tspgl::create_offscreen_context(8, 8);
  const std::string vs = tspgl::shader_source("solid2d.vert");
  const std::string bad_fs =
      "#version 330 core\nout vec4 c;\nvoid main() { c = undeclared_thing; }\n";
  const std::string msg =
      error_text([&] { tspgl::build_program(ctx->gl(), "broken", vs, bad_fs); });
  EXPECT_NE(msg.find("broken: fragment shader does not compile"), std::string::npos) << msg;
  // Mesa's compiler names the offending identifier in its log.
  EXPECT_NE(msg.find("undeclared_thing"), std::string::npos) << msg;
  tspgl::check_gl(ctx->gl(), "after a failed compile");
}

TEST(OsmesaContext, LinkErrorCarriesTheInfoLog) {
  auto ctx = tspgl::create_offscreen_context(8, 8);
  // The vertex shader's output is read by the fragment shader under another type: a link error.
  const std::string vs =
      "#version 330 core\nout vec3 v;\nvoid main() { v = vec3(0); gl_Position = vec4(0); }\n";
  const std::string fs = "#version 330 core\nin vec4 v;\nout vec4 c;\nvoid main() { c = v; }\n";
  const std::string msg = error_text([&] { tspgl::build_program(ctx->gl(), "mismatch", vs, fs); });
  EXPECT_NE(msg.find("mismatch: program does not link"), std::string::npos) << msg;
}

TEST(OsmesaContext, ShaderDirectoryOverrideIsUsedAndItsErrorsNameTheFile) {
  auto ctx = tspgl::create_offscreen_context(8, 8);
  const auto dir = tsptest::temp_dir();
  std::ofstream(dir / "solid2d.vert") << tspgl::shader_source("solid2d.vert");
  std::ofstream(dir / "solid.frag") << "#version 330 core\nvoid main() { syntax error here }\n";
  ASSERT_EQ(setenv(tspgl::kShaderDirEnv, dir.c_str(), 1), 0);
  const std::string msg =
      error_text([&] { tspgl::load_program(ctx->gl(), "solid2d.vert", "solid.frag"); });
  EXPECT_NE(msg.find("solid2d.vert + solid.frag: fragment shader does not compile"),
            std::string::npos)
      << msg;
  std::string missing;
  try {
    tspgl::shader_source("absent.frag");
  } catch (const tsp::IoError& e) {
    missing = e.what();
  }
  EXPECT_NE(missing.find("absent.frag"), std::string::npos) << missing;
  ASSERT_EQ(unsetenv(tspgl::kShaderDirEnv), 0);
  // Without the override the embedded shaders build.
  EXPECT_NE(tspgl::load_program(ctx->gl(), "solid2d.vert", "solid.frag").id(), 0u);
}

TEST(OsmesaContext, UnknownEmbeddedShaderIsAUsageError) {
  EXPECT_THROW(tspgl::shader_source("no_such_shader.frag"), tsp::UsageError);
}

TEST(OsmesaContext, InvalidSizesAreUsageErrors) {
  EXPECT_THROW(tspgl::create_offscreen_context(0, 10), tsp::UsageError);
  EXPECT_THROW(tspgl::create_offscreen_context(10, -1), tsp::UsageError);
  EXPECT_THROW(tspgl::create_offscreen_context(1 << 20, 4), tsp::UsageError);
}

TEST(OsmesaContext, GlErrorsAreReportedByName) {
  auto ctx = tspgl::create_offscreen_context(8, 8);
  ctx->gl().Enable(GLenum(0x7FFF));  // not a capability
  const std::string msg = error_text([&] { tspgl::check_gl(ctx->gl(), "glEnable(bogus)"); });
  EXPECT_NE(msg.find("glEnable(bogus): GL_INVALID_ENUM"), std::string::npos) << msg;
  EXPECT_EQ(tspgl::gl_error_name(0x1234), "GL error 0x1234");
}

TEST(OsmesaContext, TwoContextsKeepTheirOwnFramebuffers) {
  auto a = tspgl::create_offscreen_context(4, 4);
  auto b = tspgl::create_offscreen_context(4, 4);
  a->make_current();
  a->gl().ClearColor(1, 0, 0, 1);
  a->gl().Clear(GL_COLOR_BUFFER_BIT);
  b->make_current();
  b->gl().ClearColor(0, 1, 0, 1);
  b->gl().Clear(GL_COLOR_BUFFER_BIT);
  a->make_current();
  EXPECT_EQ(a->read_pixels().at(2, 2)[0], 255);
  b->make_current();
  EXPECT_EQ(b->read_pixels().at(2, 2)[1], 255);
  EXPECT_EQ(b->read_pixels().at(2, 2)[0], 0);
}

TEST(GlApi, MissingEntryPointsAreNamed) {
  const auto none = [](const char*) -> tspgl::ProcAddress { return nullptr; };
  const std::string msg = error_text([&] { tspgl::load_gl_api(none); });
  EXPECT_NE(msg.find("glTexImage3D"), std::string::npos) << msg;
  EXPECT_NE(msg.find("glReadPixels"), std::string::npos) << msg;
}

}  // namespace

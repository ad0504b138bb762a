// The EGL back end (issue 45 item 1): Mesa's software device is enumerated here and gives a 3.3
// core context whose pixels read back; an absent device index or a bad TSPPLAY_EGL_DEVICE falls
// back to OSMesa with a note or is a usage error; --gl osmesa never touches EGL.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "gl/headless.h"
#include "support/paths.h"
#include "tsp/core/error.h"

namespace {

using tspgl::HeadlessGl;

constexpr int kW = 40, kH = 30;

TEST(EglContext, MesasSoftwareDeviceDrawsAndReadsBack) {
  const auto devices = tspgl::egl_devices();
  TSPTEST_REQUIRE(!devices.empty(), "EGL enumerates no device (install libegl-mesa0)");
  std::string note = "unchanged";
  auto ctx = tspgl::create_headless_context(kW, kH, HeadlessGl::egl, -1, &note);
  EXPECT_EQ(note, "");
  EXPECT_EQ(ctx->kind().rfind("EGL device ", 0), 0u) << ctx->kind();
  EXPECT_EQ(ctx->width(), kW);
  const tspgl::GlApi& gl = ctx->gl();
  gl.ClearColor(0.2f, 0.4f, 0.6f, 0.8f);
  gl.Clear(GL_COLOR_BUFFER_BIT);
  const tsp::Image img = ctx->read_pixels();
  ASSERT_EQ(img.width, kW);
  ASSERT_EQ(img.height, kH);
  for (int y : {0, kH - 1})
    for (int x : {0, kW - 1}) {
      const std::uint8_t* p = img.at(x, y);
      EXPECT_EQ(int(p[0]), 51);
      EXPECT_EQ(int(p[1]), 102);
      EXPECT_EQ(int(p[2]), 153);
      EXPECT_EQ(int(p[3]), 204);
    }
}

TEST(EglContext, AnAbsentDeviceFallsBackToOsmesaSayingWhy) {
  std::string note;
  auto ctx = tspgl::create_headless_context(kW, kH, HeadlessGl::egl, 15, &note);
  EXPECT_EQ(ctx->kind(), "OSMesa");
  EXPECT_NE(note.find("EGL device 15 does not exist"), std::string::npos) << note;
  EXPECT_NE(note.find("drawing with OSMesa instead"), std::string::npos) << note;
}

TEST(EglContext, AutoOnlyTakesAHardwareDeviceAndOsmesaNeverEgl) {
  std::string note = "unchanged";
  auto a = tspgl::create_headless_context(kW, kH, HeadlessGl::automatic, -1, &note);
  bool hardware = false;
  for (const auto& d : tspgl::egl_devices()) hardware |= !d.software;
  EXPECT_EQ(a->kind() == "OSMesa", !hardware) << a->kind();
  EXPECT_EQ(note, "");  // auto's choice is its rule, not a fallback
  auto o = tspgl::create_headless_context(kW, kH, HeadlessGl::osmesa, -1, &note);
  EXPECT_EQ(o->kind(), "OSMesa");
}

TEST(EglContext, TheDeviceVariableIsCheckedAndUsed) {
  ::setenv("TSPPLAY_EGL_DEVICE", "x", 1);
  EXPECT_THROW(tspgl::create_headless_context(kW, kH, HeadlessGl::automatic, -1, nullptr),
               tsp::UsageError);
  ::setenv("TSPPLAY_EGL_DEVICE", "14", 1);
  std::string note;
  auto ctx = tspgl::create_headless_context(kW, kH, HeadlessGl::automatic, -1, &note);
  EXPECT_EQ(ctx->kind(), "OSMesa");
  EXPECT_NE(note.find("EGL device 14 does not exist"), std::string::npos) << note;
  ::unsetenv("TSPPLAY_EGL_DEVICE");
  EXPECT_THROW(tspgl::create_headless_context(kW, kH, HeadlessGl::egl, -2, nullptr),
               tsp::UsageError);
  EXPECT_THROW(tspgl::parse_headless_gl("vulkan", "--gl"), tsp::UsageError);
}

}  // namespace

// The headless back end: Mesa's OSMesa renders into a buffer in our memory (llvmpipe, no display
// or GPU). GL functions come from OSMesaGetProcAddress, never from libGL (docs/rendering.md).
// <GL/glcorearb.h> (through context.h) must come before <GL/osmesa.h>: osmesa.h pulls in the
// legacy <GL/gl.h>, which would otherwise hide glcorearb.h's GL 1.1 function-pointer types.
// clang-format off
#include "gl/context.h"
#include "gl/gl_error.h"
#include <GL/osmesa.h>
// clang-format on

#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

namespace tspgl {

namespace {

constexpr int kDepthBits = 24;
constexpr int kMajor = 3, kMinor = 3;
constexpr std::size_t kRgbaBytes = 4;

void release_current() {
  OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
}

struct ContextDeleter {
  void operator()(OSMesaContext ctx) const {
    if (OSMesaGetCurrentContext() == ctx) release_current();
    OSMesaDestroyContext(ctx);
  }
};
using ContextPtr = std::unique_ptr<std::remove_pointer_t<OSMesaContext>, ContextDeleter>;

ContextPtr create_core_context() {
  // clang-format off
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                         OSMESA_DEPTH_BITS, kDepthBits,
                         OSMESA_STENCIL_BITS, 0,
                         OSMESA_ACCUM_BITS, 0,
                         OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, kMajor,
                         OSMESA_CONTEXT_MINOR_VERSION, kMinor,
                         0};
  // clang-format on
  ContextPtr ctx(OSMesaCreateContextAttribs(attribs, nullptr));
  if (!ctx)
    throw tsp::GlError(
        "OSMesa could not create an OpenGL 3.3 core profile context (needs Mesa's gallium OSMesa "
        "with llvmpipe, Debian package libosmesa6)");
  return ctx;
}

// OSMesa reports its size limit only while a context is current, so bind a 1×1 buffer to ask.
void check_size(OSMesaContext ctx, int w, int h) {
  std::uint8_t probe[kRgbaBytes];
  GLint max_w = 0, max_h = 0;
  if (OSMesaMakeCurrent(ctx, probe, GL_UNSIGNED_BYTE, 1, 1)) {
    OSMesaGetIntegerv(OSMESA_MAX_WIDTH, &max_w);
    OSMesaGetIntegerv(OSMESA_MAX_HEIGHT, &max_h);
    release_current();
  }
  if (w > max_w || h > max_h)
    throw tsp::UsageError("offscreen image size " + std::to_string(w) + "x" + std::to_string(h) +
                          " exceeds OSMesa's maximum " + std::to_string(max_w) + "x" +
                          std::to_string(max_h));
}

class OsmesaContext final : public GlContext {
 public:
  OsmesaContext(int w, int h) : width_(w), height_(h), ctx_(create_core_context()) {
    check_size(ctx_.get(), w, h);
    buffer_.resize(std::size_t(w) * std::size_t(h) * kRgbaBytes);
    make_current();
    load(&OSMesaGetProcAddress, "OSMesa");
  }

  void make_current() override {
    if (!OSMesaMakeCurrent(ctx_.get(), buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
      throw tsp::GlError("OSMesaMakeCurrent failed for a " + std::to_string(width_) + "x" +
                         std::to_string(height_) + " RGBA8 buffer");
  }
  int width() const override { return width_; }
  int height() const override { return height_; }
  GetProcAddress proc_address_function() const override { return &OSMesaGetProcAddress; }
  std::string kind() const override { return "OSMesa"; }

 private:
  int width_, height_;
  // The colour buffer OSMesa draws into; read back through glReadPixels like any framebuffer.
  // Declared before ctx_ so it outlives the context: releasing a current context writes to it.
  std::vector<std::uint8_t> buffer_;
  ContextPtr ctx_;
};

}  // namespace

std::unique_ptr<GlContext> create_offscreen_context(int width, int height) {
  if (width < 1 || height < 1)
    throw tsp::UsageError("offscreen image size " + std::to_string(width) + "x" +
                          std::to_string(height) + " is invalid, expected at least 1x1");
  return std::make_unique<OsmesaContext>(width, height);
}

}  // namespace tspgl

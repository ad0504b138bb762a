#include "gl/context.h"

#include <cassert>
#include <cstdint>
#include <cstring>
#include <vector>

#include "gl/gl_error.h"

namespace tspgl {

namespace {
constexpr int kMinMajor = 3, kMinMinor = 3;
constexpr int kRgbaBytes = 4;

std::string gl_string(const GlApi& gl, GLenum name) {
  const auto* s = reinterpret_cast<const char*>(gl.GetString(name));
  return s ? s : "?";
}
}  // namespace

void GlContext::load(GetProcAddress get_proc, const std::string& backend) {
  gl_ = load_gl_api(get_proc);
  GLint major = 0, minor = 0, profile = 0;
  gl_.GetIntegerv(GL_MAJOR_VERSION, &major);
  gl_.GetIntegerv(GL_MINOR_VERSION, &minor);
  gl_.GetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  if (major * 10 + minor < kMinMajor * 10 + kMinMinor || !(profile & GL_CONTEXT_CORE_PROFILE_BIT))
    throw tsp::GlError(backend + " gave OpenGL " + gl_string(gl_, GL_VERSION) + ", expected a " +
                       std::to_string(kMinMajor) + "." + std::to_string(kMinMinor) +
                       " core profile context");
  check_gl(gl_, backend + " context creation");
}

void GlContext::finish() {
  gl_.Finish();
  check_gl(gl_, "glFinish");
}

tsp::Image GlContext::read_pixels() {
  return read_pixels(0, 0, canvas_width(), canvas_height());
}

tsp::Image GlContext::read_pixels(int x, int y, int w, int h) {
  assert(x >= 0 && y >= 0 && w > 0 && h > 0 && x + w <= canvas_width() &&
         y + h <= canvas_height());
  tsp::Image img(w, h);
  GLint read_fbo = 0, pack_alignment = 0;
  gl_.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fbo);
  gl_.GetIntegerv(GL_PACK_ALIGNMENT, &pack_alignment);
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, canvas_.fbo);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<std::uint8_t> bottom_up(img.rgba.size());
  gl_.ReadPixels(x, y, w, h, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  gl_.PixelStorei(GL_PACK_ALIGNMENT, pack_alignment);
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_fbo));
  check_gl(gl_, "glReadPixels");
  // GL's row 0 is the bottom one; images are stored top row first.
  const std::size_t row = std::size_t(w) * kRgbaBytes;
  for (int y = 0; y < h; ++y)
    std::memcpy(img.rgba.data() + row * y, bottom_up.data() + row * (h - 1 - y), row);
  return img;
}

std::string GlContext::vendor() const { return gl_string(gl_, GL_VENDOR); }

std::string GlContext::describe() const {
  return gl_string(gl_, GL_RENDERER) + ", OpenGL " + gl_string(gl_, GL_VERSION);
}

}  // namespace tspgl

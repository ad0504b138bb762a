#include "render/cpu_pass.h"

#include <algorithm>
#include <cctype>

#include "gl/gl_error.h"

namespace tspgl {

namespace {
// The texture unit the picture is bound to (above the compositor's ten).
constexpr int kImageUnit = 10;
}  // namespace

bool software_renderer(const std::string& renderer) {
  std::string r = renderer;
  std::transform(r.begin(), r.end(), r.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const char* name : {"llvmpipe", "softpipe", "swrast", "software rasterizer"})
    if (r.find(name) != std::string::npos) return true;
  return false;
}

CpuPass::CpuPass(const GlApi& gl) : gl_(gl), blit_(load_program(gl, "cpu_image.vert", "cpu_image.frag")) {
  gl_.GenTextures(1, &texture_);
  gl_.GenVertexArrays(1, &vao_);
  blit_.use();
  gl_.Uniform1i(blit_.uniform("image"), kImageUnit);
  check_gl(gl_, "setting up the CPU caster's pass");
}

CpuPass::~CpuPass() {
  gl_.DeleteTextures(1, &texture_);
  gl_.DeleteVertexArrays(1, &vao_);
}

CastStats CpuPass::draw(const CastScene& scene, CastRect rect) {
  if (rect.x1 <= rect.x0 || rect.y1 <= rect.y0) rect = {0, 0, scene.width, scene.height};
  rect.x0 = std::max(rect.x0, 0);
  rect.y0 = std::max(rect.y0, 0);
  rect.x1 = std::min(rect.x1, scene.width);
  rect.y1 = std::min(rect.y1, scene.height);
  const CastStats drawn = cast_rays(scene, rect, 0, rgba_);
  if (rect.x1 <= rect.x0 || rect.y1 <= rect.y0) return drawn;
  gl_.ActiveTexture(GL_TEXTURE0 + kImageUnit);
  gl_.BindTexture(GL_TEXTURE_2D, texture_);
  if (scene.width != width_ || scene.height != height_) {
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, scene.width, scene.height, 0, GL_RGBA, GL_FLOAT,
                   nullptr);
    width_ = scene.width;
    height_ = scene.height;
  }
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl_.PixelStorei(GL_UNPACK_ROW_LENGTH, scene.width);
  gl_.PixelStorei(GL_UNPACK_SKIP_PIXELS, rect.x0);
  gl_.PixelStorei(GL_UNPACK_SKIP_ROWS, rect.y0);
  gl_.TexSubImage2D(GL_TEXTURE_2D, 0, rect.x0, rect.y0, rect.x1 - rect.x0, rect.y1 - rect.y0,
                    GL_RGBA, GL_FLOAT, rgba_.data());
  gl_.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  gl_.PixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
  gl_.PixelStorei(GL_UNPACK_SKIP_ROWS, 0);
  gl_.ActiveTexture(GL_TEXTURE0);
  blit_.use();
  gl_.BindVertexArray(vao_);
  gl_.DrawArrays(GL_TRIANGLES, 0, 3);
  check_gl(gl_, "blending the CPU caster's picture");
  return drawn;
}

}  // namespace tspgl

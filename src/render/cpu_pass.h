// The GL side of the CPU ray caster (render/cpu_caster.h): casts a frame's rays on the CPU and
// blends the picture into the bound render target with the GL caster's "over", so the rest of
// the frame (background, surface, partial-image reuse, resolve, read-back) is unchanged.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "gl/shader.h"
#include "render/cpu_caster.h"

namespace tspgl {

/// True when `renderer` (GL_RENDERER) names a software rasteriser (llvmpipe, softpipe, swrast):
/// where --backend auto casts on the CPU. Never throws.
bool software_renderer(const std::string& renderer);

/// One picture texture and its blit program in a GL context (current, outliving it). Use from
/// the context's thread; not copyable.
class CpuPass {
 public:
  /// Builds the program. Throws tsp::GlError.
  explicit CpuPass(const GlApi& gl);
  ~CpuPass();
  CpuPass(const CpuPass&) = delete;
  CpuPass& operator=(const CpuPass&) = delete;
  /// Casts scene's rays in rect (the whole target when empty) and blends them over the bound
  /// target, which must be scene.width × scene.height with blending set. Returns what the
  /// cast did. Throws tsp::GlError.
  CastStats draw(const CastScene& scene, CastRect rect);

 private:
  const GlApi& gl_;
  Program blit_;
  GLuint texture_ = 0, vao_ = 0;
  int width_ = 0, height_ = 0;  ///< the texture's size
  std::vector<float> rgba_;
};

}  // namespace tspgl

// The one-pass ray caster's GL programs: which variant a frame draws with (a typed key, not
// #define strings), the GLSL source of each (volume_ray.frag's walk with its sampling part,
// docs/rendering.md "The caster in parts"), the constants shared with the C++ side, and a cache
// that compiles each variant the first time it is used.
#pragma once
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gl/shader.h"

namespace tspgl {

/// How the caster samples a full-resolution textured brick: one part of the shader each.
enum class RayVariant {
  segments,       ///< segments cut at each run's ends (ray_segments.glsl)
  preintegrated,  ///< the same, pre-integrated between each segment's ends (TSP_PREINT)
  adaptive,       ///< segments of m spacings from the step map (ray_adaptive.glsl)
  refined,        ///< segments refined where the TF bends (ray_refine.glsl)
  clipped,        ///< plane samples against a clip solid's intervals (ray_planes.glsl)
  clipped_interval,  ///< an intersection: each ray cut to one kept interval (ray_planes.glsl)
};
/// The number of RayVariant values.
inline constexpr int kRayVariants = 6;

/// The variant's name in messages ("segments", "clipped", …).
const char* to_string(RayVariant v);

/// GLSL `const` declarations of the constants the shaders share with C++ (ray_constants.h,
/// tsp::kRefineSamples, tsp::kLevelTfRows, tsp::ClipRegion::kMaxProbes), bit-exact.
std::string glsl_constants();

/// The #define lines and the shader files (in order) prepended to volume_ray.frag for v.
std::pair<std::string, std::vector<std::string>> ray_sources(RayVariant v);

/// The caster's programs, each built on first use (llvmpipe's compiler takes seconds over the
/// clip code, which frames without probes should not pay). Not thread-safe: one GL context.
class RayPrograms {
 public:
  /// A cache building into gl's context; `prepare` runs once on each program built (its
  /// texture units). Builds nothing yet.
  RayPrograms(const GlApi& gl, std::function<void(const Program&)> prepare);
  /// The program of v, built now if it was not. Throws tsp::GlError (compile or link, with the
  /// info log), tsp::IoError (a $TSPPLAY_SHADER_DIR file).
  const Program& get(RayVariant v);

 private:
  const GlApi& gl_;
  std::function<void(const Program&)> prepare_;
  std::array<std::optional<Program>, kRayVariants> programs_;
};

}  // namespace tspgl

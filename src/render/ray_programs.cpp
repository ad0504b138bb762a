#include "render/ray_programs.h"

#include <cstdio>

#include "render/ray_constants.h"
#include "tsp/clip/probe.h"
#include "tsp/frame/refine.h"
#include "tsp/metric/level_tf.h"

namespace tspgl {

namespace {

// A GLSL float literal that reads back as exactly x (9 significant digits round-trip a float).
std::string glsl_float(const char* name, float x) {
  char digits[32];
  std::snprintf(digits, sizeof digits, "%.9g", double(x));
  std::string literal = digits;
  if (literal.find_first_of(".e") == std::string::npos) literal += ".0";  // a float, not an int
  return "const float " + std::string(name) + " = " + literal + ";\n";
}

std::string glsl_int(const char* name, int x) {
  return "const int " + std::string(name) + " = " + std::to_string(x) + ";\n";
}

}  // namespace

const char* to_string(RayVariant v) {
  switch (v) {
    case RayVariant::segments: return "segments";
    case RayVariant::preintegrated: return "preintegrated";
    case RayVariant::adaptive: return "adaptive";
    case RayVariant::refined: return "refined";
    case RayVariant::clipped: return "clipped";
    case RayVariant::clipped_interval: return "clipped_interval";
  }
  return "?";
}

std::string glsl_constants() {
  return glsl_float("kOpaque", ray::kOpaque) + glsl_float("kNudge", ray::kNudge) +
         glsl_float("kFlatGradient", ray::kFlatGradient) +
         glsl_int("kClipFlag", ray::kClipFlag) + glsl_int("kLevelRowUnit", ray::kLevelRowUnit) +
         glsl_float("kLevelTfRows", float(tsp::kLevelTfRows)) +
         glsl_int("kRefineSamples", tsp::kRefineSamples) +
         glsl_int("kMaxProbes", tsp::ClipRegion::kMaxProbes);
}

std::pair<std::string, std::vector<std::string>> ray_sources(RayVariant v) {
  // TSP_CLIP: 0 without probes (clip_on() is the constant false), 1 the general solid, 2 one
  // kept interval per ray. TSP_SEGMENTS marks the variants sampling in segments (no probes).
  std::string defines;
  const char* part = "ray_segments.glsl";
  switch (v) {
    case RayVariant::segments:
      defines = "#define TSP_CLIP 0\n#define TSP_SEGMENTS 1\n";
      break;
    case RayVariant::preintegrated:
      defines = "#define TSP_CLIP 0\n#define TSP_SEGMENTS 1\n#define TSP_PREINT 1\n";
      break;
    case RayVariant::adaptive:
      defines = "#define TSP_CLIP 0\n#define TSP_SEGMENTS 1\n#define TSP_ADAPTIVE 1\n";
      part = "ray_adaptive.glsl";
      break;
    case RayVariant::refined:
      defines = "#define TSP_CLIP 0\n#define TSP_SEGMENTS 1\n#define TSP_REFINE 1\n";
      part = "ray_refine.glsl";
      break;
    case RayVariant::clipped:
      defines = "#define TSP_CLIP 1\n";
      part = "ray_planes.glsl";
      break;
    case RayVariant::clipped_interval:
      defines = "#define TSP_CLIP 2\n";
      part = "ray_planes.glsl";
      break;
  }
  return {defines, {"box_ray.glsl", "sample_tf.glsl", "clip.glsl", "ray_walk.glsl",
                    "ray_levels.glsl", part}};
}

RayPrograms::RayPrograms(const GlApi& gl, std::function<void(const Program&)> prepare)
    : gl_(gl), prepare_(std::move(prepare)) {}

const Program& RayPrograms::get(RayVariant v) {
  std::optional<Program>& p = programs_[std::size_t(v)];
  if (!p) {
    auto [defines, parts] = ray_sources(v);
    p.emplace(load_program_with(gl_, "box.vert", "volume_ray.frag", parts,
                                defines + glsl_constants()));
    prepare_(*p);
  }
  return *p;
}

}  // namespace tspgl

// The one-pass caster's program variants and the constants both casters share: the GLSL reads
// them from glsl_constants() alone (no shader file restates one), each parses back to the exact
// C++ value, and each variant's source names its own sampling part.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>

#include "gl/embedded_shaders.h"
#include "gl/shader.h"
#include "render/cpu_sample.h"
#include "render/ray_programs.h"
#include "render/slice_compositor.h"
#include "tsp/clip/probe.h"
#include "tsp/frame/refine.h"
#include "tsp/metric/level_tf.h"

namespace tspgl {
namespace {

constexpr const char* kShared[] = {"kOpaque",      "kNudge",         "kFlatGradient",
                                   "kClipFlag",    "kLevelRowUnit",  "kLevelTfRows",
                                   "kRefineSamples", "kMaxProbes"};

// The value of `const TYPE name = VALUE;` in GLSL text, as GLSL reads it (a float constant is a
// 32-bit float); NaN when it is not there.
double glsl_constant(const std::string& src, const std::string& name) {
  std::smatch m;
  const std::regex line("const (int|float) " + name + " = ([-+0-9.e]+);");
  if (!std::regex_search(src, m, line)) return std::nan("");
  return m[1] == "float" ? double(std::stof(m[2].str())) : std::stod(m[2].str());
}

TEST(RayPrograms, SharedConstantsComeFromTheCppSideBitExact) {
  const std::string g = glsl_constants();
  EXPECT_EQ(glsl_constant(g, "kOpaque"), double(ray::kOpaque));
  EXPECT_EQ(glsl_constant(g, "kNudge"), double(ray::kNudge));
  EXPECT_EQ(glsl_constant(g, "kFlatGradient"), double(ray::kFlatGradient));
  EXPECT_EQ(glsl_constant(g, "kClipFlag"), ray::kClipFlag);
  EXPECT_EQ(glsl_constant(g, "kLevelRowUnit"), ray::kLevelRowUnit);
  EXPECT_EQ(glsl_constant(g, "kLevelTfRows"), tsp::kLevelTfRows);
  EXPECT_EQ(glsl_constant(g, "kRefineSamples"), tsp::kRefineSamples);
  EXPECT_EQ(glsl_constant(g, "kMaxProbes"), tsp::ClipRegion::kMaxProbes);
  // A float constant is written as a float literal (GLSL 330 would read "16" as an int).
  EXPECT_NE(g.find("const float kLevelTfRows = 16.0;"), std::string::npos) << g;
  // The CPU caster and the page codes use the same values.
  EXPECT_EQ(detail::kOpaque, ray::kOpaque);
  EXPECT_EQ(BrickPages::kClipFlag, ray::kClipFlag);
  EXPECT_EQ(BrickPages::kLevelRowUnit, ray::kLevelRowUnit);
}

TEST(RayPrograms, NoShaderFileRestatesASharedConstant) {
  for (const EmbeddedShader& s : embedded_shaders())
    for (const char* name : kShared)
      EXPECT_TRUE(std::isnan(glsl_constant(s.source, name)))
          << s.name << " declares " << name << ": it comes from glsl_constants()";
}

TEST(RayPrograms, EachVariantHasItsOwnSamplingPartAndDefines) {
  auto part = [](RayVariant v) { return ray_sources(v).second.back(); };
  EXPECT_EQ(part(RayVariant::segments), "ray_segments.glsl");
  EXPECT_EQ(part(RayVariant::preintegrated), "ray_segments.glsl");
  EXPECT_EQ(part(RayVariant::adaptive), "ray_adaptive.glsl");
  EXPECT_EQ(part(RayVariant::refined), "ray_refine.glsl");
  EXPECT_EQ(part(RayVariant::clipped), "ray_planes.glsl");
  EXPECT_EQ(part(RayVariant::clipped_interval), "ray_planes.glsl");
  EXPECT_NE(ray_sources(RayVariant::preintegrated).first.find("TSP_PREINT"), std::string::npos);
  EXPECT_NE(ray_sources(RayVariant::clipped_interval).first.find("TSP_CLIP 2"),
            std::string::npos);
  for (int i = 0; i < kRayVariants; ++i) {
    const auto [defines, files] = ray_sources(RayVariant(i));
    // Every part exists (embedded) and exactly one defines the sampling function.
    int defining = 0;
    for (const std::string& f : files)
      defining += shader_source(f).find("void sample_run(") != std::string::npos;
    EXPECT_EQ(defining, 1) << to_string(RayVariant(i));
  }
}

}  // namespace
}  // namespace tspgl

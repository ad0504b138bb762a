// The constants both ray casters share, held against each other: the GLSL caster's `const`
// lines (shaders/volume_ray.frag, sample_tf.glsl, as embedded) against the C++ side they copy
// (BrickPages, tsp::kRefineSamples, tsp::kLevelTfRows) and the CPU caster's (render/cpu_sample.h).
// A constant changed on one side only fails here instead of drawing two different pictures.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "gl/shader.h"
#include "render/cpu_sample.h"
#include "render/slice_compositor.h"
#include "tsp/frame/refine.h"
#include "tsp/metric/level_tf.h"

namespace tspgl {
namespace {

// The value of `const TYPE name = VALUE;` in a shader file's source.
double shader_constant(const std::string& file, const std::string& name) {
  const std::string src = shader_source(file);
  std::smatch m;
  const std::regex line("const (int|float) " + name + " = ([-0-9.e]+);");
  EXPECT_TRUE(std::regex_search(src, m, line)) << name << " not in " << file;
  // As GLSL reads it: a float constant is a 32-bit float.
  return m.size() > 2 ? (m[1] == "float" ? double(std::stof(m[2].str())) : std::stod(m[2].str())) : -1;
}

TEST(CasterConstants, GlslAndCppAgree) {
  EXPECT_EQ(shader_constant("volume_ray.frag", "kOpaque"), double(detail::kOpaque));
  EXPECT_EQ(shader_constant("volume_ray.frag", "kNudge"), double(detail::kNudge));
  EXPECT_EQ(shader_constant("volume_ray.frag", "kClipFlag"), BrickPages::kClipFlag);
  EXPECT_EQ(shader_constant("volume_ray.frag", "kClipFlag"), detail::kClipFlag);
  EXPECT_EQ(shader_constant("volume_ray.frag", "kLevelRowUnit"), BrickPages::kLevelRowUnit);
  EXPECT_EQ(shader_constant("volume_ray.frag", "kLevelRowUnit"), detail::kLevelRowUnit);
  EXPECT_EQ(shader_constant("volume_ray.frag", "kLevelTfRows"), tsp::kLevelTfRows);
  EXPECT_EQ(shader_constant("volume_ray.frag", "kRefineSamples"), tsp::kRefineSamples);
  EXPECT_EQ(shader_constant("sample_tf.glsl", "kFlatGradient"), double(detail::kFlatGradient));
}

}  // namespace
}  // namespace tspgl

// The constants both ray casters share — the GL caster (shaders/volume_ray.frag and its parts)
// and the CPU caster (cpu_caster.*): written once here; the GLSL sees them through
// glsl_constants() (ray_programs.h), which every program's source starts with.
#pragma once

namespace tspgl::ray {

/// Opacity at or above which a ray stops (early ray termination).
inline constexpr float kOpaque = 0.999f;
/// Ray parameter nudge when finding the brick a point lies in.
inline constexpr float kNudge = 1e-3f;
/// Gradient length (value range per voxel) over which lighting fades in.
inline constexpr float kFlatGradient = 1e-3f;
/// A textured page's code: + kClipFlag when the clip surface may cross the brick.
inline constexpr int kClipFlag = 512;
/// A textured page's code: + row · kLevelRowUnit for a level brick's TF row.
inline constexpr int kLevelRowUnit = 1024;

}  // namespace tspgl::ray

// Geometry in sample coordinates (sample i of an axis sits at coordinate i): the closed box a
// voxel box covers, shared by the slicers, the renderer and later the clipping probes.
#pragma once
#include <array>

#include "tsp/core/types.h"

namespace tsp {

/// Closed axis-aligned box [lo, hi] per axis, in sample coordinates.
struct Aabb {
  std::array<double, 3> lo{0, 0, 0};
  std::array<double, 3> hi{0, 0, 0};
  bool operator==(const Aabb&) const = default;
};

/// The geometric box of voxel box `box` in a volume of dims d: [lo, min(hi, D − 1)] per axis, so
/// that bricks and octree nodes tile [0, D − 1]³ with shared faces.
Aabb geometric_box(const Box& box, const Dims& d);

}  // namespace tsp

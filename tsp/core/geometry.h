// Geometry in sample coordinates (sample i of an axis sits at coordinate i): the closed box a
// voxel box covers, shared by the slicers, the renderer and later the clipping probes.
#pragma once
#include <array>
#include <string>

#include "tsp/core/types.h"

namespace tsp {

/// Closed axis-aligned box [lo, hi] per axis, in sample coordinates.
struct Aabb {
  std::array<double, 3> lo{0, 0, 0};
  std::array<double, 3> hi{0, 0, 0};
  bool operator==(const Aabb&) const = default;
};

/// A box holding nothing (lo > hi on every axis): the start of a union.
Aabb empty_aabb();
/// True when box holds no point (lo > hi on some axis). Never throws.
bool is_empty(const Aabb& box);
/// Grows box to hold point p. Never throws.
void grow(Aabb& box, const std::array<double, 3>& p);
/// Grows box to hold other (nothing when other is empty). Never throws.
void unite(Aabb& box, const Aabb& other);
/// The points in both a and b (empty when they do not meet). Never throws.
Aabb intersection(const Aabb& a, const Aabb& b);
/// The centre of box. Never throws.
std::array<double, 3> centre(const Aabb& box);
/// The length of box's diagonal. Never throws.
double diagonal(const Aabb& box);

/// The geometric box of voxel box `box` in a volume of dims d: [lo, min(hi, D − 1)] per axis, so
/// that bricks and octree nodes tile [0, D − 1]³ with shared faces.
Aabb geometric_box(const Box& box, const Dims& d);

/// Largest ratio between a grid's largest and smallest voxel size that is drawn: beyond it the
/// thin axis rounds to nothing when the box is fitted to the view (every frame blank).
inline constexpr double kMaxSpacingRatio = 1e6;

/// Why a grid's origin and voxel spacing cannot be drawn, "" when they can: every spacing a
/// positive normal number (no zero, denormal, infinity or NaN), every origin finite, the
/// largest spacing within kMaxSpacingRatio of the smallest. Never throws.
std::string spacing_problem(const std::array<double, 3>& origin,
                            const std::array<double, 3>& spacing);

}  // namespace tsp

// The separating-axis test between a tetrahedron and an axis-aligned box (paper 000 §4): they
// are disjoint exactly when their projections onto one of 25 axes are — the box's 3 face
// normals, the tetrahedron's 4 face normals, and the 18 cross products of a box edge direction
// with a tetrahedron edge.
#pragma once
#include <array>

#include "tsp/core/geometry.h"

namespace tsp {

/// A point in space.
using Vec3 = std::array<double, 3>;

/// True when the closed tetrahedron (any orientation; a degenerate one is tested as the
/// flat set it spans) and the closed box share a point. Never throws.
bool tet_box_overlap(const std::array<Vec3, 4>& tet, const Aabb& box);

}  // namespace tsp

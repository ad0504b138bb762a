// Rounding onto the voxelizers' sample lattices, shared by scan conversion (scan_convert) and
// the two-buffer voxelizer (two_buffer): a sample within kEdgeTolerance lattice spacings of an
// edge, face or span end counts as on it, so the cells on both sides take it (the voxelizer's
// pass mask keeps the first).
#pragma once
#include <cmath>

namespace tsp::detail {

/// Samples within this many lattice spacings of an edge or face count as on it.
inline constexpr double kEdgeTolerance = 1e-9;

/// The first lattice index at or above u (within the tolerance). u must fit an int. Never throws.
inline int first_at_or_above(double u) { return int(std::ceil(u - kEdgeTolerance)); }

/// The last lattice index at or below u (within the tolerance). u must fit an int. Never throws.
inline int last_at_or_below(double u) { return int(std::floor(u + kEdgeTolerance)); }

}  // namespace tsp::detail

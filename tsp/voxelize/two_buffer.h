// Voxelizer C (paper 003 §2, "two-buffer"; §3.1 for anti-aliasing): one tetrahedron at a time,
// cell order. Seen along +z, its faces that face the viewer are scan-converted into a front
// buffer and the others into a back buffer — per scan line the triangle's extent from its edges
// (form_buffers: x, depth and value stepped incrementally along the edges from one row to the
// next), along the row depth and value stepped incrementally (scan_convert) — each buffer
// holding, per pixel (a column of voxels), the depth and the value where the ray enters and
// leaves the cell. Between the two buffers every voxel of the column inside [front, back] takes
// the value stepped incrementally from the front value (voxelize_between_two_buffers), exact for
// the field linear over the tetrahedron.
//
// Anti-aliasing as the paper's accumulation volume buffer: K³ passes (K = 1..kMaxTwoBufferK per
// axis), each the whole voxelization on the grid shifted by a sub-voxel offset — the centres of
// a K³ sub-grid, or, jittered, each moved by a fixed pseudo-random amount inside its sub-cell —
// accumulated per voxel (a mask of the passes already taken, so a sample on a face shared by two
// tetrahedra counts once, and their sum). A voxel is inside when at least half its passes hit.
// The K passes that share an (x, y) offset (a sub-pixel) share the two buffers: their depths
// and values are scan-converted once and each pass steps its own depth offset between them, so
// a tetrahedron is scan-converted K² times, not K³.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "tsp/voxelize/tetrahedra.h"
#include "tsp/voxelize/voxelizer.h"

namespace tsp::detail {

/// Per-voxel accumulation of the two-buffer passes: pass p taken (bit p of 128), and the sum.
struct PassBuffers {
  int k = 1;                                 ///< samples per axis
  std::vector<std::array<double, 3>> offset; ///< per pass: the shift, in voxels, from the centre
  std::vector<std::array<std::uint64_t, 2>> taken;
  std::vector<double> sum;
};

/// The K³ pass offsets (in voxels, each in (−½, ½)), pass p = (s_z·K + s_y)·K + s_x: sub-cell
/// centres ((s + ½)/K − ½ per axis), jittered by a fixed pseudo-random amount within
/// ±kJitterShare of a sub-cell when jitter — x and y by the sub-pixel (s_x, s_y), so the K
/// passes p mod K² share them, z by the pass. K = 1 without jitter is the voxel centre alone.
/// Never throws.
std::vector<std::array<double, 3>> pass_offsets(int k, bool jitter);

/// Share of a sub-cell a jittered sample may move from its centre, each way.
inline constexpr double kJitterShare = 0.35;

/// Voxelizes tetrahedron t of mesh into the passes of voxels [t0, t1] (one tile) of grid by the
/// two-buffer method, skipping samples already taken. Returns the samples it took. Never throws.
std::int64_t two_buffer_tet(const TetMesh& mesh, std::int64_t t, const VoxelGrid& grid,
                            const int t0[3], const int t1[3], PassBuffers& b);

}  // namespace tsp::detail

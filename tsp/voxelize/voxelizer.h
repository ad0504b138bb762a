// Sampling a tetrahedral mesh on a regular grid (paper 000 §4, "voxelizer A"): tetrahedra are
// binned into tiles of the grid by the separating-axis test, then each tile, in parallel,
// walks its tetrahedra in index order and samples the voxel centres inside each by barycentric
// interpolation (exact for a field linear over the tetrahedron). A voxel takes the first
// tetrahedron (lowest index) that contains it, so shared faces are never sampled twice; a voxel
// no tetrahedron contains is outside. Outside voxels are then padded with the value of the
// nearest inside voxel (breadth-first, 6-neighbourhood) so filtering at the boundary never
// pulls towards garbage.
#pragma once
#include <array>
#include <cstdint>
#include <span>

#include "tsp/core/geometry.h"
#include "tsp/core/types.h"
#include "tsp/voxelize/tetrahedra.h"

namespace tsp {

/// A regular grid in space: voxel (i, j, k) sits at origin + (i, j, k)·spacing.
struct VoxelGrid {
  Dims dims;
  std::array<double, 3> origin{0, 0, 0};
  std::array<double, 3> spacing{1, 1, 1};
  bool operator==(const VoxelGrid&) const = default;
};

/// What a voxelization found, for reports and benchmarks.
struct VoxelizeStats {
  std::int64_t tets = 0;          ///< tetrahedra sampled
  std::int64_t tile_tests = 0;    ///< tet–tile pairs tested by the separating-axis test
  std::int64_t tile_entries = 0;  ///< pairs that overlapped (the bins' total size)
  std::int64_t inside = 0;        ///< voxels inside the mesh
};

/// Samples mesh on grid into values (dims.count() floats, x fastest) and inside (1 = inside the
/// mesh, 0 = outside), padding outside voxels as described above (all 0 when nothing is
/// inside). Runs on `threads` workers (0: all cores). Never throws (asserts on sizes).
VoxelizeStats voxelize(const TetMesh& mesh, const VoxelGrid& grid, std::span<float> values,
                       std::span<std::uint8_t> inside, int threads = 0);

/// Pads the outside voxels of values (inside[i] == 0) with the value of the nearest inside
/// voxel by breadth-first distance over the 6-neighbourhood (ties: the first reached in x, y, z
/// order). Leaves values untouched when nothing is inside. Never throws.
void pad_outside(std::span<float> values, std::span<const std::uint8_t> inside, Dims dims);

}  // namespace tsp

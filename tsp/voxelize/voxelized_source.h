// A MeshSource seen as a VolumeSource: every step voxelized onto one grid chosen at open, with
// its stencil. The grid rule (docs/inputs.md "Unstructured grids"): cubic voxels over the union
// of every step's bounding box; their size is --voxel-size, or the longest edge over
// --resolution − 1 samples, or by default the median cell size of the first step (the cube
// root of the cells' volumes), held to 16–256 samples on the longest edge.
#pragma once
#include <memory>
#include <vector>

#include "tsp/source/mesh_source.h"
#include "tsp/voxelize/voxelizer.h"

namespace tsp {

/// How cell data is sampled.
enum class CellDataMode {
  constant,  ///< piecewise constant: a voxel takes its cell's value
  points,    ///< averaged to the points first (each point the mean of its cells), then linear
};

/// Options of the voxelizing source.
struct VoxelizeOptions {
  int resolution = 0;         ///< samples on the longest edge (0: by rule)
  double voxel_size = 0;      ///< physical voxel edge (0: by rule); exclusive with resolution
  CellDataMode cell_data = CellDataMode::constant;
  SampleOptions sample;       ///< voxelizer, hexahedron sampling, antialiasing, workers
};

/// Default grid limits on the longest edge, and the largest grid any option may ask for.
inline constexpr int kMinDefaultResolution = 16;
inline constexpr int kMaxDefaultResolution = 256;
inline constexpr std::int64_t kMaxVoxelizedSamples = std::int64_t(1) << 31;

/// The grid for meshes spanning bounds whose typical cell edge is cell_size (≤ 0: unknown,
/// then the largest default). Throws UsageError on bad options (both given, non-positive,
/// a grid beyond max_samples: the uniform grid's kMaxVoxelizedSamples, more for an adaptive
/// octree that never holds it whole). Never throws otherwise.
VoxelGrid choose_grid(const Aabb& bounds, double cell_size, const VoxelizeOptions& options,
                      std::int64_t max_samples = kMaxVoxelizedSamples);

/// Median over cells of the cube root of the cell's volume (the sum of its tetrahedra's); 0 for
/// a mesh without volume. Never throws.
double median_cell_size(const TetMesh& mesh);
/// The same median from the cells' volumes (cells of volume 0 left out). Never throws.
double median_cell_size(const std::vector<double>& volumes);

/// Wraps source (reading every step's bounds now to fix the grid). Throws what the source
/// throws, UsageError on bad options, FormatError when the meshes have no extent or are flat
/// along an axis. Its read_step throws FormatError naming the step when voxelize() refuses the
/// work (kVisitsPerItem) or no voxel lies inside any cell.
std::unique_ptr<VolumeSource> voxelized_source(std::unique_ptr<MeshSource> source,
                                               const VoxelizeOptions& options);

}  // namespace tsp

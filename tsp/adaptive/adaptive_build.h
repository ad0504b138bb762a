// Building a .tsp from a mesh series with Leven's adaptive octree (paper 000 §4.2; issue 31):
// `tspplay build MESH --octree-error E`.
#pragma once
#include <cstdint>
#include <string>

#include "tsp/build/build.h"
#include "tsp/source/mesh_source.h"
#include "tsp/voxelize/voxelized_source.h"

namespace tsp {

/// Largest finest grid an adaptive build accepts (samples): it is never held whole, only the
/// octree's reachable bricks are, so the limit is the .tsp format's per step (16 GiB of float32;
/// the uniform build's is kMaxVoxelizedSamples, a step it must hold in memory).
inline constexpr std::int64_t kMaxAdaptiveSamples = kMaxStepSamples;

/// Options of an adaptive build.
struct AdaptiveOptions {
  double error = 0;       ///< homogeneity threshold E ≥ 0, in data units or (relative) a fraction
  bool relative = false;  ///< E is a fraction of the field's finite range over all steps
  VoxelizeOptions voxelize;  ///< the finest grid's rule and the sampler (as the uniform build)
  BuildOptions build;        ///< brick size (0: default_brick_size), range, threads, deflate,
                             ///< progress, field name (origin/spacing/partition: not used)
};

/// What an adaptive build did (paper 000 Fig. 14's quantities).
struct AdaptiveReport {
  BuildReport build;             ///< as the uniform build's (source_bytes: of the finest grid)
  Dims dims;                     ///< the finest grid
  double threshold = 0;          ///< E in data units
  int nodes = 0;                 ///< octree nodes holding data (not below a stop)
  int stopped = 0;               ///< of those, stopped above the finest level
  int complete_nodes = 0;        ///< nodes of the complete octree over the finest grid
  std::int64_t brick_bytes = 0;  ///< stored brick samples written, 2 bytes each, all steps
  std::int64_t complete_brick_bytes = 0;  ///< the same for the uniform build of that grid
  std::int64_t cell_list_bytes = 0;       ///< the cell lists on disk
  double octree_seconds = 0;     ///< reading the steps and subdividing
  double voxelize_seconds = 0;   ///< sampling the reachable nodes' bricks
};

/// Reads source's steps, subdivides the complete octree over the finest grid top-down
/// (subdivide(): a node splits while some cell is smaller than its voxels and the field's spread
/// there exceeds E), samples every reachable node's brick from its own cells (leaves at the
/// finest spacing, stopped and inner nodes on their level lattices: point samples of the mesh),
/// and writes out_path (format version 3: octree/stopped) through a temporary name. Memory holds
/// one step's mesh, per-cell boxes and one brick per worker; cell lists and samples go to scratch
/// files beside out_path. Throws UsageError (bad options or grid), FormatError/IoError (the
/// input, naming it), IoError (the output); never leaves a partial out_path.
AdaptiveReport build_adaptive_tsp(MeshSource& source, const std::string& out_path,
                                  const AdaptiveOptions& options);

}  // namespace tsp

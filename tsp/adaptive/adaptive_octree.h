// The adaptive octree's shape (Leven et al., paper 000 §4.2, Fig. 6): which nodes of the complete
// octree over the finest grid keep splitting, decided top-down from the mesh's cells.
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "tsp/adaptive/cell_lists.h"
#include "tsp/build/scratch_file.h"
#include "tsp/core/geometry.h"
#include "tsp/source/mesh_source.h"
#include "tsp/tree/octree.h"
#include "tsp/voxelize/voxelized_source.h"

namespace tsp {

/// What the subdivision needs of a mesh series, from one read of every step, on disk: per cell
/// its box and size, per step and cell its value range. When every step has as many cells as
/// step 0 they are taken for the same cells (a moving or fixed mesh): one cell list per node
/// serves every step, the boxes spanning all steps; otherwise (a remeshed series) every step
/// has its own cells and lists.
struct MeshScan {
  /// Per list step: per cell lo x, y, z, hi x, y, z and its size (its thinnest extent,
  /// volume / largest box edge²).
  static constexpr int kSummary = 7;
  Aabb bounds;                 ///< every step's points
  double median_cell = 0;      ///< median cell size of step 0 (the grid rule's default)
  ValueRange data;             ///< finite values over all steps ({0, 0} when none)
  std::int64_t nonfinite = 0;  ///< NaN/Inf values over all steps
  int steps = 0;               ///< time steps
  bool shared = true;          ///< the same cells at every step
  std::vector<std::int64_t> cells;   ///< cells per list step
  std::unique_ptr<DiskLists<float>> summary;  ///< per list step, kSummary floats per cell
  std::unique_ptr<DiskLists<float>> ranges;   ///< per step: min, max of each cell's finite
                                              ///< values (min > max when none)
  Mesh last;                   ///< the last step's mesh (prepared), kept for the sampler's
                               ///< first step (one read fewer)
  /// Lists per node: 1 when shared, else one per step.
  int list_steps() const { return shared ? 1 : steps; }
  /// The list step serving step t.
  int list_step(int t) const { return shared ? 0 : t; }
};

/// Readies a step's mesh for sampling as the uniform voxelizer would (cell data averaged to the
/// points in CellDataMode::points). Never throws but bad_alloc.
void prepare_mesh(Mesh& mesh, CellDataMode mode);

/// Reads every step of source once (prepare_mesh'ed), with scratch data in dir. Throws what the
/// source throws, FormatError naming the input when a step has no cells, IoError from the
/// scratch files.
MeshScan scan_mesh(MeshSource& source, CellDataMode mode, const std::string& dir);

/// The subdivision's outcome.
struct Subdivision {
  std::vector<std::uint8_t> stopped;  ///< per node: 1 where the octree stops above the leaves
  int reachable = 0;                  ///< nodes that hold data (not below a stop)
  int stopped_count = 0;              ///< nodes stopped above the finest level
};

/// Node id's sample region on grid in space, widened by its sample spacing plus one finest voxel
/// on every side (the antialiasing voxelizers' sub-samples stay within it). Never throws.
Aabb node_region(const Octree& octree, const VoxelGrid& grid, int id);

/// Splits the complete octree over grid top-down: the root holds every cell; a node splits while
/// some cell of its lists is smaller than its voxel edge (its largest sample spacing) and the
/// field's spread over its cells exceeds `error` at some step (data units); a node without
/// cells stops (no data there). Each child's lists (the parent's cells whose box meets
/// node_region) go to lists under node · scan.list_steps() + list step (lists must have room
/// for octree.size() · list_steps() keys); only one level's flags and one list step's cell
/// summary are in memory. Throws IoError.
Subdivision subdivide(const Octree& octree, const VoxelGrid& grid, const MeshScan& scan,
                      double error, CellLists& lists);

}  // namespace tsp

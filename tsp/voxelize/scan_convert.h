// Voxelizer B (paper 003, Kaufman-style): incremental scan conversion of one tetrahedron onto a
// K× supersampled grid — per sub-sample plane its cross-section polygon, per row of the polygon
// its span, along the span the value stepped incrementally — accumulated per voxel (the
// accumulation buffer: a sum and a mask of the sub-samples already taken, so a sub-sample on a
// shared face counts once). Used by voxelize() with VoxelizerKind::scan.
#pragma once
#include <cstdint>
#include <vector>

#include "tsp/voxelize/tetrahedra.h"
#include "tsp/voxelize/voxelizer.h"

namespace tsp::detail {

/// Per-voxel accumulation: the sub-samples taken (bit s of K³ ≤ 64) and their values' sum.
struct ScanBuffers {
  int k = 1;
  std::vector<std::uint64_t> taken;
  std::vector<double> sum;
};

/// Scan-converts tetrahedron t of mesh into the sub-samples of voxels [t0, t1] (one tile) of
/// grid, skipping sub-samples already taken. Returns the sub-samples it took. Never throws.
std::int64_t scan_tet(const TetMesh& mesh, std::int64_t t, const VoxelGrid& grid, const int t0[3],
                      const int t1[3], ScanBuffers& b);

}  // namespace tsp::detail

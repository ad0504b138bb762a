// Sampling an unstructured mesh on a regular grid (paper 000 §4, "voxelizer A"): cells are
// binned into tiles of the grid (tetrahedra by the separating-axis test, whole hexahedra by
// their boxes), then each tile, in parallel, walks its cells in index order and samples the
// voxel centres inside each: a tetrahedron by barycentric interpolation (exact for a field
// linear over it); a hexahedron, in isoparametric mode, by its trilinear map (the parametric
// point found by Newton's method, as VTK's probe does), else through its tetrahedra. A voxel
// takes the first cell (lowest index; within a cell its first tetrahedron) that contains it, so
// shared faces are never sampled twice; a voxel no cell contains is outside. Outside voxels are
// then padded with the value of the nearest inside voxel (breadth-first, 6-neighbourhood) so
// filtering at the boundary never pulls towards garbage.
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

/// How hexahedra (and voxels) are sampled.
enum class HexSampling {
  isoparametric,  ///< whole, trilinear in their parametric coordinates (VTK's interpolation)
  tetrahedra,     ///< through their conforming tetrahedra, linear in each (paper 000)
};

/// Which voxelizer samples the cells.
enum class VoxelizerKind {
  locate,  ///< A (paper 000): each voxel centre located in a cell, interpolated there
  scan,    ///< B (paper 003): tetrahedra scan-converted onto K× sub-samples, averaged per voxel
  two_buffer,  ///< C (paper 003 §2): front and back faces into two buffers, voxels between them
               ///< stepped incrementally; K³ shifted (optionally jittered) passes accumulated
};

/// Largest anti-aliasing factor of the two-buffer voxelizer (K³ passes fit a 128-bit mask).
inline constexpr int kMaxTwoBufferK = 5;

/// Largest anti-aliasing factor of the scan voxelizer (K³ sub-samples fit a 64-bit mask).
inline constexpr int kMaxAntialias = 4;

/// The work voxelize() accepts: every tetrahedron (or whole hexahedron) visits the voxels of its
/// bounding box, and the visits of one step may total at most kVisitsPerItem × (voxels + cells'
/// tetrahedra and hexahedra), and never less than kMinVisitBudget. Meshes whose cells tile
/// space make a few visits per voxel and per tetrahedron; a mesh of many overlapping large cells
/// (50,000 copies of one cell spanning the domain) makes thousands and is refused. Each visit
/// counts what it costs: K³ with the scan and two-buffer voxelizers' --antialias K (checked
/// before sampling), and kNewtonIterationVisits more per iteration of a whole hexahedron's
/// Newton solve that finds the voxel outside it (counted while sampling, which stops when the
/// budget is spent; solves that find a voxel are bounded by the grid, each voxel found once).
inline constexpr std::int64_t kVisitsPerItem = 64;
/// The least budget (about a second of tetrahedron visits).
inline constexpr std::int64_t kMinVisitBudget = std::int64_t(1) << 30;
/// What one Newton iteration on a hexahedron's trilinear map costs, in tetrahedron visits
/// (measured: about 130 ns against 8 ns per visit of the tetrahedra path, one thread).
inline constexpr std::int64_t kNewtonIterationVisits = 16;

/// How voxelize() samples.
struct SampleOptions {
  VoxelizerKind kind = VoxelizerKind::locate;
  HexSampling hex = HexSampling::isoparametric;  ///< locate only
  int antialias = 1;  ///< scan and two_buffer: K, 1..kMaxAntialias (scan) or kMaxTwoBufferK; a
                      ///< voxel is inside when at least half its K³ sub-samples are, and holds
                      ///< their mean
  bool jitter = false;  ///< two_buffer: each sub-sample moved by a fixed pseudo-random amount
                        ///< inside its sub-cell (paper 003 §3.1's jittered pattern)
  int threads = 0;    ///< workers; 0 = all cores
};

/// What a voxelization did, for reports and benchmarks.
struct VoxelizeStats {
  std::int64_t tets = 0;          ///< tetrahedra sampled
  std::int64_t hexahedra = 0;     ///< hexahedra sampled whole
  std::int64_t tile_tests = 0;    ///< tet–tile pairs tested by the separating-axis test
  std::int64_t tile_entries = 0;  ///< cell–tile pairs binned (the bins' total size)
  std::int64_t inside = 0;        ///< voxels inside the mesh
  std::int64_t visits = 0;        ///< voxels of the cells' bounding boxes, summed over cells
  std::int64_t newton_iterations = 0;  ///< Newton iterations run on whole hexahedra
  std::int64_t newton_missed = 0;  ///< of them, those of solves that found the voxel outside
};

/// Samples mesh (validated by check_mesh) on grid into values (dims.count() floats, x fastest)
/// and inside (1 = inside the mesh, 0 = outside), padding outside voxels as described above
/// (all 0 when nothing is inside). Throws FormatError (naming no file; the caller adds it) when
/// the cells' bounding boxes would make more visits than the budget above allows, before any
/// voxel is sampled, or when Newton's iterations spend the rest of it while sampling. Asserts
/// on sizes and an antialias factor outside 1..kMaxAntialias.
VoxelizeStats voxelize(const Mesh& mesh, const VoxelGrid& grid, std::span<float> values,
                       std::span<std::uint8_t> inside, const SampleOptions& options = {});

/// Pads the outside voxels of values (inside[i] == 0) with the value of the nearest inside
/// voxel by breadth-first distance over the 6-neighbourhood (ties: the first reached in x, y, z
/// order). Leaves values untouched when nothing is inside. Never throws.
void pad_outside(std::span<float> values, std::span<const std::uint8_t> inside, Dims dims);

}  // namespace tsp

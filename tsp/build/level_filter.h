// The LOD level bricks' filter (spec §14, docs/formats.md "Levels"): a level brick's sample at
// voxel coordinate p with spacing f along an axis is a separable box filter of width f centred on
// p — weights ½, 1, …, 1, ½ over p − f/2 … p + f/2, the box of one coarse cell integrated with
// linear interpolation — whose window shrinks symmetrically at the grid's faces. The value depends
// on p and f only, never on the node, so neighbours at one level agree on shared faces (Leven's
// border continuity), and a linear field is reproduced exactly at every level.
#pragma once
#include <optional>
#include <span>
#include <vector>

#include "tsp/core/types.h"
#include "tsp/tree/octree.h"

namespace tsp {

/// Reusable buffers of filter_level (one per thread).
struct LevelFilterScratch {
  std::vector<float> a, b;
};

/// Fills out with the level brick of lattice l (l.count() floats, x fastest) filtered from one
/// step's volume vol (d.count() floats, x fastest). With clamp, finite samples are clamped into it
/// first; non-finite samples are left out of the averages (NaN when a window has none, which the
/// builder's sanitizer then maps like any NaN). Never throws (asserts sizes).
void filter_level(std::span<const float> vol, Dims d, const BrickLattice& l,
                  const std::optional<ValueRange>& clamp, LevelFilterScratch& scratch,
                  std::vector<float>& out);

/// RMS difference over the finite voxels of own between vol and the trilinear reconstruction of
/// them from level (the output of filter_level for l); 0 when own has no finite voxel.
double level_residual(std::span<const float> vol, Dims d, const BrickLattice& l, const Box& own,
                      std::span<const float> level, const std::optional<ValueRange>& clamp);

}  // namespace tsp

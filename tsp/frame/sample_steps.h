// Adaptive sampling (issue 9 item 2): the ray caster samples the volume every m·spacing, the
// step multiplier m picked per cell of kStepCell³ voxels from how fast the colour changes under
// the TF in and around the cell, so smooth or nearly uniform regions cost fewer samples and the
// quality knob is a bound on the colour change one step may pass over. The renderer draws with
// one TF row per multiplier, its opacity corrected for that step (spec §9). GL-free;
// docs/rendering.md "Adaptive sampling".
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "tsp/core/types.h"
#include "tsp/metric/transfer_function.h"

namespace tsp {

/// The step multipliers a cell may get, finest first (rows of the renderer's TF table).
inline constexpr std::array<double, 7> kStepMultipliers{1, 1.5, 2, 3, 4, 6, 8};

/// Side, in voxels, of the cells a step multiplier is picked for.
inline constexpr int kStepCell = 4;

/// Cells per axis of the step grid of a volume of dims samples (cell c holds samples
/// [c·kStepCell, (c + 1)·kStepCell)).
std::array<int, 3> step_grid(Dims dims);

/// How fast the colour changes in the step-grid cells one brick's samples reach.
struct CellVariations {
  std::array<int, 3> first{}, count{};  ///< the cells, in the step grid
  std::vector<float> v;                  ///< per cell (x fastest): see SampleVariation::cells
};

/// How fast bricks' colours change under one TF. Immutable once made; any thread may share it.
class SampleVariation {
 public:
  /// For tf over bricks whose 16-bit codes are quantized over `quantized` (code c is the value
  /// quantized.lo + c/65535·width), the code → entry map the renderer's nearest lookup uses.
  /// Never throws.
  SampleVariation(const TransferFunction& tf, ValueRange quantized);
  /// For the codes of the samples in box (x fastest), per step-grid cell the box reaches: the
  /// largest change of any premultiplied colour channel (colour × opacity per voxel, and that
  /// opacity) between samples p and p + one along an axis, both in box, p in the cell (0: none,
  /// or uniform). Never throws.
  CellVariations cells(const std::uint16_t* codes, const Box& box) const;

 private:
  std::vector<std::uint16_t> entry_;          ///< per code
  std::vector<std::array<float, 4>> colour_;  ///< per entry, premultiplied
};

/// Per cell of a step grid of `grid` cells holding `variation` (x fastest): the index into
/// kStepMultipliers of the largest m whose step L = spacing·m keeps variation·L ≤ tol in every
/// cell within ceil(L / kStepCell) cells of it (a step from the cell reaches no further), 0
/// when none does. Asserts spacing > 0 and matching sizes.
std::vector<std::uint8_t> step_rows(const std::vector<float>& variation, std::array<int, 3> grid,
                                    double spacing, double tol);

}  // namespace tsp

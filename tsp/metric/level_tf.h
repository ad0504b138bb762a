// Transfer functions for coarse LOD levels (LaMar et al., seed paper 002, §4.3: a lower
// resolution needs its own TF). A level-k brick holds the field filtered to 2^k voxels; the
// voxels one of its samples stands for spread around it by the level's residual σ (the RMS
// difference between the voxels and their reconstruction from the level, TspTree::level_error).
// Classified after filtering, a thin TF band that those voxels cross vanishes or turns to stripes.
// Classified as the expected colour of the voxels instead — the TF averaged over a normal
// distribution of width σ around the sample's value, E[α] and E[α·rgb] — the band survives as
// a wider, fainter one of the same weight. Rows of σ on a geometric ladder, so a brick picks
// the row nearest its own σ.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "tsp/metric/transfer_function.h"

namespace tsp {

/// Rows of the level TF table: row 0 is the TF itself (σ = 0), rows 1 … kLevelTfRows − 1 blur
/// it by level_tf_sigma(row).
inline constexpr int kLevelTfRows = 16;
/// σ of row 1 and of the last row, as a share of the TF's domain width.
inline constexpr double kLevelTfSigmaMin = 1.0 / 1024, kLevelTfSigmaMax = 0.5;

/// σ of row `row` as a share of the TF's domain width: 0 for row 0, then geometric from
/// kLevelTfSigmaMin to kLevelTfSigmaMax. Asserts 0 <= row < kLevelTfRows.
double level_tf_sigma(int row);

/// The row whose σ is nearest `sigma` (a share of the domain width) on a log scale; 0 below
/// half of row 1's σ (the brick is drawn with the TF itself). Never throws.
int level_tf_row(double sigma);

/// tf's entries averaged over a normal distribution of the value with standard deviation
/// sigma (a share of the domain width): entry j gets α = Σ w·α_i and colour Σ w·α_i·c_i / α
/// over the entries i, weights w of the normal density at the entry centres' distance,
/// normalised; values beyond the domain take the edge entries, as the lookup clamps. Straight
/// (not premultiplied) colours, opacity per voxel like tf's. sigma <= 0: tf's entries.
/// With prior (one weight per entry: how many samples of the data take the entry's value), the
/// normal weights are multiplied by it — the voxels a sample stands for take the values the data
/// takes, not any value near the sample's (a background value next to an opaque value no sample
/// takes stays clear); where the prior is 0 over the whole kernel, the plain normal weights.
std::vector<Rgba> blurred_entries(const TransferFunction& tf, double sigma,
                                  std::span<const double> prior = {});

/// Share of the mean count added to every entry's prior: half the blur's weight follows the
/// data's distribution, half the plain normal kernel. Measured at level 1 and 2 (docs/results.md):
/// prior alone (0) helped the histogram map and hurt the sparse one; 1 kept the sparse map within
/// 0.2 ΔE of no prior and the histogram map within 0.5 of its best.
inline constexpr double kLevelTfPriorFloor = 1.0;

/// The prior of blurred_entries for tf from a value histogram (counts of equal bins over
/// `over`): per entry, the count of the bin holding its value (0 outside `over`) plus
/// kLevelTfPriorFloor times the mean of those counts; empty when the histogram is. Never throws.
std::vector<double> entry_prior(const TransferFunction& tf, std::span<const std::uint64_t> counts,
                                ValueRange over);

}  // namespace tsp

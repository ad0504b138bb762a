// The data-driven default transfer function (issue 29 item 4): opacity where the data is
// interesting, from the file's value histogram, not from fixed places in its range. A value
// is as opaque as it is rare: the background that fills most of the volume (the most common
// values) is transparent, the values few samples take — fronts between two states, vortex
// cores, a plume in still air — are opaque, and values the data never takes cost nothing
// (no sample holds them, except between two samples that straddle them: the front itself).
// Colours are ParaView's Cool to Warm over the domain.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "tsp/metric/transfer_function.h"

namespace tsp {

/// A value histogram: counts of equal bins over `over` (a .tsp's /histogram and value range).
struct ValueHistogram {
  std::span<const std::uint64_t> counts;  ///< one count per bin
  ValueRange over;                        ///< the bins' span, lo < hi
};

/// Opacity of the rarest value (a value no sample takes). Per voxel of spacing (spec §9).
inline constexpr double kHistogramTfMaxOpacity = 0.8;
/// Exponent of the rarity: opacity = kHistogramTfMaxOpacity · rarity^kHistogramTfGamma, so values
/// a tenth as common as the background stay nearly clear.
inline constexpr double kHistogramTfGamma = 2.0;
/// Rarity below which a value is clear (opacity 0): the values within a tenth of the log-count
/// range of the most common one — the background — are wholly transparent, so the TSP tree skips
/// the regions that hold only them (a faint haze would make every node textured).
inline constexpr double kHistogramTfClearRarity = 0.1;
/// Share of the samples in each tail of the distribution that is shown whatever its counts: a
/// value with less than this share of the samples below it (or above it) gets opacity
/// kHistogramTfMaxOpacity · (1 − share/kHistogramTfTailShare)^kHistogramTfGamma, so the extremes
/// of a smooth, peaked distribution (a pressure field's vortex cores, a plume's hottest air)
/// show as structures, not only the few rarest voxels.
inline constexpr double kHistogramTfTailShare = 0.1;
/// Half-width, in bins, of the triangular filter the counts are smoothed with (one noisy bin
/// does not make a band).
inline constexpr int kHistogramTfSmoothBins = 2;

/// Rarity of a count when the counts cannot tell values apart (all equal, or none).
inline constexpr double kHistogramTfFlatRarity = 0.5;

/// Rarity of every bin, in [0, 1], from the counts smoothed by the triangular filter: with
/// L = log(1 + c), (L_max − L) / (L_max − L_min) where L_max and L_min are the largest and the
/// least L of the bins that hold samples, so the most common value has rarity 0 and the least
/// common one (and every empty bin) rarity 1; kHistogramTfFlatRarity everywhere when
/// L_max = L_min. Never throws.
std::vector<double> histogram_rarity(std::span<const std::uint64_t> counts);

/// Per bin, the share of the samples on the nearer side of it: min(F, 1 − F) with F the share
/// below the bin's middle (half its own count included); all 1 (no tail) without samples.
/// Never throws.
std::vector<double> histogram_tail_share(std::span<const std::uint64_t> counts);

/// The histogram TF over `domain`: entry j has the Cool to Warm colour of its place in the
/// domain and opacity the larger of kHistogramTfMaxOpacity · rarity^kHistogramTfGamma (0 below
/// kHistogramTfClearRarity) and the tail opacity (kHistogramTfTailShare) of the bin of h holding
/// its value, rarity and tails taken among the bins the domain overlaps (of those bins alone; a
/// value outside h.over: rarity 1, no sample takes it). Some sample always takes an
/// opaque value, so the picture is never empty: the rarest value present has the largest
/// opacity. Throws UsageError on an invalid domain or h.over (not finite, lo ≥ hi) or
/// entries < 2.
TransferFunction histogram_transfer_function(const ValueHistogram& h, ValueRange domain,
                                             int entries = kDefaultTfEntries);

}  // namespace tsp

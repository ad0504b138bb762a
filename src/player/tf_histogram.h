// The histogram the TF editor draws under its curve (docs/player.md "Transfer function"): counts
// of equal bins over the TF's domain. From the file's stored histogram (256 bins over the whole
// quantization range) while enough of its bins fall inside the domain; otherwise — a skewed
// field whose colour range is fitted to its bulk, where the stored bins inside the domain are
// two or three — counted afresh over the domain from the samples of one step (at most
// kHistogramBricks bricks, spread evenly; inside the data only, for a file with a stencil).
// GL- and ImGui-free, so tests check it directly.
#pragma once
#include <cstdint>
#include <vector>

#include "tsp/core/types.h"
#include "tsp/store/brick_store.h"

namespace tspplayer {

/// Fewest stored bins inside the domain that the editor draws from; fewer: counted afresh.
inline constexpr double kMinStoredBins = 32;
/// Most leaf bricks read to count a step's histogram.
inline constexpr int kHistogramBricks = 64;

/// Counts of `counts.size()` equal bins over `over`.
struct EditorHistogram {
  tsp::ValueRange over;        ///< the bins' span (the TF's domain)
  std::vector<double> counts;  ///< one count per bin (stored counts split by overlap: fractional)
  int step = -1;  ///< the step counted (−1: the file's stored histogram of every step)
};

/// The editor's histogram over `over` in `bins` bins (≥ 1) for store `bricks` showing `step`:
/// the stored histogram redistributed onto the bins (each stored bin split by overlap) when at
/// least kMinStoredBins of its bins lie in `over`, else step's samples counted. Throws what
/// read_brick throws.
EditorHistogram editor_histogram(const tsp::BrickStore& bricks, int step, tsp::ValueRange over,
                                 int bins);

}  // namespace tspplayer

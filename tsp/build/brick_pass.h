// tsp/build: the builder's pass 2 (brick-major quantization and statistics); internal to
// build.cpp, which runs pass 1 and assembles the file.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "tsp/build/build.h"
#include "tsp/build/scratch_file.h"
#include "tsp/store/tsp_writer.h"
#include "tsp/tree/moments.h"
#include "tsp/tree/tsp_tree.h"

namespace tsp::detail {

/// Phase name of pass 2 in progress reports.
inline constexpr const char* kPhaseBricks = "bricks";

/// The stencil's scratch files (sources with a stencil only): the leaf and level bricks' inside
/// flags as floats (a level brick's flag is the level filter of the flags, inside when ≥ ½).
struct StencilScratch {
  ScratchFile* leaves = nullptr;
  ScratchFile* levels = nullptr;
};

/// What pass 2 adds up besides the per-node accumulators.
struct BrickPassResult {
  std::vector<std::uint64_t> histogram;     ///< over the quantization range, kHistogramBins
  /// Per stored brick: own voxels inside at some step (leaf bricks, and the level bricks of
  /// stopped nodes; 0 for the others).
  std::vector<std::int64_t> inside_voxels;
};

/// Pass 2: reads each stored brick's series (skipping the bricks below a stop of an adaptive
/// octree, whose scratch holds nothing; a stopped node's statistics come from its level brick) from the scratch files (and drops it), applies the
/// NaN/Inf rule, quantizes it and writes it to writer, fills its leaf's accumulators in acc (by
/// TSP node id) and adds to the histogram, on `threads` workers. With a partition, only this
/// process's bricks: rank 0 also writes the bricks the other ranks send (their accumulators into
/// acc, their residuals into level_errors) and gets the histogram summed over the ranks; the
/// other ranks (writer null) send theirs instead. Throws IoError, Error.
BrickPassResult run_brick_pass(const TspTree& tree, ScratchFile& scratch, ScratchFile& levels,
                               StencilScratch stencil, TspWriter* writer, ValueRange range,
                               std::vector<NodeAccum>& acc, std::span<float> level_errors,
                               BuildPartition* partition, int threads, const ProgressFn& progress,
                               std::int64_t total_bytes);

}  // namespace tsp::detail

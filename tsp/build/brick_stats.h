// Statistics of one leaf brick for every time node, from the brick's whole time series.
#pragma once
#include <cstdint>
#include <span>

#include "tsp/core/types.h"
#include "tsp/tree/moments.h"
#include "tsp/tree/time_tree.h"

namespace tsp {

/// Fills out[τ] (one per time node of time) with the statistics of the voxels in own over the
/// span of τ. series holds the brick's samples over all steps, [T][samples box, x fastest],
/// already free of NaN/Inf; own must lie inside samples. range_width is the COV fallback
/// divisor. Per-voxel temporal mean/M2 are combined up the time tree, voxel groups are combined
/// with Chan's formula. With a stencil, use (one flag per sample of the samples box) keeps only
/// the voxels flagged 1; empty means all. Never throws (asserts on inconsistent sizes).
void brick_time_stats(const TimeTree& time, const Box& samples, const Box& own,
                      std::span<const float> series, double range_width, std::span<NodeAccum> out,
                      std::span<const std::uint8_t> use = {});

}  // namespace tsp

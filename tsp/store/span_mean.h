// The per-voxel temporal mean of one brick over a span of steps: what textures a span under
// SpanStep::mean (spec §5: the temporal error measures each step's deviation from this mean).
#pragma once
#include "tsp/store/brick_cache.h"

namespace tsp {

/// Samples of brick whose codes are the rounded per-voxel mean of its codes at steps t0..t1
/// (codes are linear in the value, so this is the mean value's code); with a stencil, the flags
/// of the middle step ⌊(t0 + t1)/2⌋ and each inside voxel's mean over the steps where it is
/// inside. Reads every step through cache (thread-safe as BrickCache::get is); t0 == t1 returns
/// cache.get(brick, t0) itself. Asserts 0 ≤ t0 ≤ t1 < steps; throws what the store throws.
BrickSamples span_mean(BrickCache& cache, int brick, int t0, int t1);

}  // namespace tsp

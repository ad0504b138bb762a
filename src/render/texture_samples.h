// The samples a brick texture holds: one step's bricks, or a span's per-voxel mean.
#pragma once
#include "tsp/frame/texture_cache.h"
#include "tsp/store/brick_cache.h"
#include "tsp/store/span_mean.h"

namespace tspgl {

/// Samples for key (level and brick as stored): bricks.get(brick, t0), or for a mean key
/// tsp::span_mean over t0..t1. Thread-safe as BrickCache is; throws what the store throws.
inline tsp::BrickSamples texture_samples(tsp::BrickCache& bricks, const tsp::TextureKey& key) {
  return key.is_mean() ? tsp::span_mean(bricks, key.brick, key.t0, key.t1)
                       : bricks.get(key.brick, key.t0);
}

}  // namespace tspgl

// Samples of the CPU ray caster in batches, in SIMD lanes (Google Highway, dispatched at run time
// to the widest target this CPU has: AVX-512, AVX2, SSE4 or scalar): the trilinear read, the
// TF's nearest lookup and Blinn–Phong with its six gradient taps for up to kMaxBatch positions at
// once — the same formulas as cpu_sample.h's scalar Sampler, lane by lane. The textures must be
// single-channel (no stencil) and small enough for 32-bit byte offsets (batch_ready()).
#pragma once
#include <cstdint>

#include "render/cpu_sample.h"

namespace tspgl::detail {

/// Positions per batch (16 lanes of AVX-512 at most).
inline constexpr int kMaxBatch = 16;

/// Positions in texel coordinates, structure of arrays.
struct Positions {
  alignas(64) float x[kMaxBatch], y[kMaxBatch], z[kMaxBatch];
};

/// Colours, structure of arrays (premultiplied).
struct Colours {
  alignas(64) float r[kMaxBatch], g[kMaxBatch], b[kMaxBatch], a[kMaxBatch];
};

/// True when the batch functions can read smp's texels (one channel, offsets within 2^31 bytes).
bool batch_ready(const Sampler& smp);

/// The point lookups through `row` (K entries) of the scalars at the first n positions, each
/// position clamped into the brick's box first; with `shade`, lit as Sampler::shade lights them
/// at the (unclamped) positions. Never throws; thread-safe.
void sample_batch(const Sampler& smp, const BrickView& b, const float* row, const Positions& p,
                  int n, bool shade, Colours& out);

/// Colours c lit at positions p (Sampler::shade, lane by lane); transparent ones unchanged.
/// Never throws; thread-safe.
void shade_batch(const Sampler& smp, const BrickView& b, const Positions& p, int n, Colours& c);

/// cut_sample on the first n colours, each standing for k[i] (≤ 1 or more: a slab of a level
/// brick) of its segment, in SIMD (the power as exp(k·log(1 − α)): within a few ulps of
/// std::pow). Never throws; thread-safe.
void cut_batch(const float* k, int n, Colours& c);

}  // namespace tspgl::detail

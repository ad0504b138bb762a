// Refinement (issue 29): the ray caster samples each segment of the slice planes' grid at its
// middle, except where the transfer function bends or jumps between the scalars of neighbouring
// segments' middles — a thin band or a one-voxel jump the segment crosses. Those segments are
// sampled kRefineSamples times through a TF corrected for the finer step, so the band is drawn
// where it lies instead of where the coarse samples happen to fall (the wood grain of a
// one-voxel jump). The test costs no lookup of its own: the TF is cut into nearly straight
// pieces (tf_pieces) and each entry's piece rides in the point lookup's opacity. GL-free;
// docs/rendering.md, `--refine-tol`.
#pragma once
#include <vector>

#include "tsp/metric/transfer_function.h"

namespace tsp {

/// Samples a refined segment takes (a segment of the default spacing ½ is sampled every 1/12
/// voxel; 8 cost 1.2–1.4× the plain frame on llvmpipe for a p99 lower by about 1, 4 missed the
/// shock's target: docs/results.md).
inline constexpr int kRefineSamples = 6;

/// The default refinement tolerance: how far the TF may stray from a straight line through the
/// colours over a piece of its entries (premultiplied colour and opacity at the spacing).
inline constexpr double kDefaultRefineTol = 0.3;

/// The TF's entries cut into pieces over which it is nearly straight: per entry, the index of its
/// piece (0, 1, … rising with the entry). Each piece is a run of entries a … e that every entry
/// between stays within tol (in every channel of the premultiplied TF with its opacity
/// corrected for `spacing` voxels, spec §9) of the chord from entry a to entry e, and each is as
/// long as it can be, taken greedily from entry 0. So between any two entries of one piece the TF
/// strays by at most 2·tol from their own chord — the colour a sample at the middle of a linear
/// run of values between them stands for — and a pair in different pieces is where refinement
/// looks closer. Asserts spacing > 0 and tol ≥ 0. Never throws.
std::vector<int> tf_pieces(const TransferFunction& tf, double spacing, double tol);

}  // namespace tsp

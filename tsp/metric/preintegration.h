// Pre-integrated transfer function (Engel, Kraus & Ertl 2001): for a ray segment of `length`
// voxels along which the scalar runs linearly from the front sample's TF coordinate to the back
// sample's, the exactly composited colour of the nearest-entry table the renderer uses — so a
// coarse spacing still sees every thin TF feature the segment crosses.
#pragma once
#include <vector>

#include "tsp/metric/transfer_function.h"

namespace tsp {

/// Premultiplied colour and opacity of the segment from TF coordinate u_front to u_back (in
/// [0, 1]: entry j covers [j/K, (j+1)/K)) over `length` voxels of tf's entries (opacity per
/// voxel), composited front to back bin by bin: C = Σ T·c·(1 − (1 − α)^ℓ), T ← T·(1 − α)^ℓ with
/// ℓ each bin's share of the length. Asserts length > 0.
Rgba integrate_segment(const TransferFunction& tf, double u_front, double u_back, double length);

/// The K × K table of integrate_segment over the entry centres, u = (j + ½)/K, front index
/// fastest: table[f + K·b]. Cost O(K³) (about 5.6 M bin steps for K = 256), spread over
/// `threads` workers (0: all cores). Asserts length > 0.
std::vector<Rgba> preintegrate(const TransferFunction& tf, double length, int threads = 0);

}  // namespace tsp

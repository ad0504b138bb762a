// The TF editor's handles over a detailed transfer function (docs/player.md "Transfer
// function"): moving a handle warps the TF between its neighbours in place — the values between
// two handles stretch with them and each entry's colour and opacity shift by the handles'
// changes, interpolated — so the detailed auto map keeps its shape instead of becoming straight
// segments through the handles. GL- and ImGui-free, so tests check it directly.
#pragma once
#include <span>
#include <vector>

#include "tsp/metric/transfer_function.h"

namespace tspplayer {

/// Most knots a TF is shown by; a TF with more gets kSampledHandles evenly spaced handles.
inline constexpr int kMaxKnotHandles = 24;
/// Handles placed evenly over a TF with more than kMaxKnotHandles knots.
inline constexpr int kSampledHandles = 9;

/// The handles as they were placed and the TF then (what moving them warps).
struct TfHandles {
  tsp::TransferFunction base;        ///< the TF when the handles were placed
  std::vector<tsp::TfPoint> placed;  ///< the handles then, by increasing value
};

/// Handles for tf: its knots (the first and last entries and every entry where the table's
/// slope changes, so a piecewise-linear TF is shown by its own points) when at most
/// kMaxKnotHandles, else kSampledHandles evenly spaced samples; base = tf. Never throws but
/// bad_alloc.
TfHandles place_handles(const tsp::TransferFunction& tf);

/// The handles `points` of a TF over `from` carried onto `tf`, the same map stretched over its
/// own domain (a colour range typed or fitted, tsp::rescaled): every handle kept, at the same
/// place relative to the domain and with its colour; base = tf. (Placed again from the stretched
/// table, a moved handle went back to its even place and knots shifted or merged: a fit left 7
/// points of 9.) Never throws but bad_alloc.
TfHandles rescale_handles(std::span<const tsp::TfPoint> points, tsp::ValueRange from,
                          const tsp::TransferFunction& tf);

/// tf's colour at v, interpolated linearly between entry centres (lookup() takes the nearest
/// entry). Never throws.
tsp::Rgba sample_tf(const tsp::TransferFunction& tf, double v);

/// h.base with the handles moved from h.placed to `moved` (same count and order): values between
/// two handles are stretched with them, each entry's colour and opacity shifted by the two
/// handles' changes interpolated between them; beyond the outermost handles, their change.
/// Nothing moved: h.base itself; a piecewise-linear TF shown by its knots stays what from_points
/// makes of the moved knots. Throws tsp::UsageError when the counts differ.
tsp::TransferFunction warp_handles(const TfHandles& h, std::span<const tsp::TfPoint> moved);

/// Where handle i of `points` (by increasing value) may go: x clamped between its neighbours,
/// so handles keep their order. Never throws.
double clamp_handle_x(std::span<const tsp::TfPoint> points, int i, double x);

/// Adds a handle at x with colour c (opacity c.a) to the handles of `current` (the TF they now
/// show): they are placed again over `current`, so the rest of the curve stays as it is; the
/// new handle's change from current's colour there bends the curve towards it. Returns its
/// index. Never throws but bad_alloc.
int add_handle(TfHandles& h, std::vector<tsp::TfPoint>& points,
               const tsp::TransferFunction& current, double x, tsp::Rgba c);

/// Removes handle i (of at least three) from the handles of `current`: the curve between its
/// neighbours becomes straight (beyond an end handle: flat at the new end's colour); the
/// handles are placed again over the result, which it returns. Never throws but bad_alloc.
tsp::TransferFunction remove_handle(TfHandles& h, std::vector<tsp::TfPoint>& points,
                                    const tsp::TransferFunction& current, int i);

}  // namespace tspplayer

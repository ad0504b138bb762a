// A flat domain opened readable: the vertical exaggeration a view starts with when the data's
// height is a sliver of its width (WRF's 480 km × 6 km), and how the picture names it ("z × 30").
#pragma once
#include <array>
#include <string>

#include "tsp/core/geometry.h"

namespace tsp {

/// A box whose height is under this share of its larger horizontal edge is flat.
inline constexpr double kFlatAspect = 0.1;
/// Largest automatic exaggeration (the player's axis-scale field goes to 100).
inline constexpr double kMaxAutoExaggeration = 100;

/// The axis scale a view of the physical box `frame` opens with: {1, 1, k} when frame's z
/// extent is under kFlatAspect of its larger x or y extent, k the round number (1, 2, 3 or
/// 5 × 10^n, at most kMaxAutoExaggeration) nearest a third of that ratio, so the box shows about
/// a third as tall as wide (WRF Katrina's 470 km × 5.6 km: 30); {1, 1, 1} otherwise, and for an
/// empty box or one without height. Never throws.
std::array<double, 3> vertical_exaggeration(const Aabb& frame);

/// The stretch of `scale` as the picture names it: "z × 30" ("x × 2, z × 30" for several axes,
/// "x" instead of "×" when ascii, for the bitmap font of exported frames); "" for {1, 1, 1}.
/// Never throws.
std::string exaggeration_text(const std::array<double, 3>& scale, bool ascii = false);

}  // namespace tsp

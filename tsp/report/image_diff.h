// Per-pixel colour difference of two images in CIE L*u*v* (spec §10): ΔE*uv statistics and an
// optional grey-scale difference image.
#pragma once
#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "tsp/report/image.h"

namespace tsp {

/// Summary of the per-pixel ΔE*uv between two equally sized images.
struct DiffStats {
  double mean = 0;            ///< mean ΔE over all pixels
  double p99 = 0;             ///< 99th percentile ΔE (nearest rank: the ⌈0.99·n⌉-th smallest)
  double max = 0;             ///< largest ΔE
  std::int64_t pixels = 0;    ///< number of pixels compared
  int width = 0, height = 0;  ///< size of both images
};

/// s as JSON (mean, p99, max, pixels, width, height): what `diff --json` prints and Python's
/// tspplay.diff returns. Never throws.
void to_json(nlohmann::json& j, const DiffStats& s);

/// ΔE that maps to white in the difference image (grey level = min(255, round(ΔE·255/10))).
inline constexpr double kDiffImageFullScale = 10.0;

/// Compares a and b pixel by pixel. Each pixel's RGB is taken as sRGB after compositing over
/// black (c·α/255, in the encoded values, as GL blending does); converted to L*u*v* (D65) with
/// tsp/color.h. When diff_image is given it receives an opaque grey image of the ΔE (scale
/// kDiffImageFullScale). name_a / name_b appear in errors. Throws UsageError when the sizes differ.
DiffStats diff_images(const Image& a, const Image& b, Image* diff_image = nullptr,
                      const std::string& name_a = "first image",
                      const std::string& name_b = "second image");

}  // namespace tsp

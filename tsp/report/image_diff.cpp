#include "tsp/report/image_diff.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>
#include <vector>

#include "tsp/core/color.h"
#include "tsp/core/error.h"

namespace tsp {

namespace {

constexpr double kMax8 = 255.0;
// The percentile as a fraction kPercentNum / kPercentDen, so the rank is exact integer arithmetic.
constexpr std::size_t kPercentNum = 99, kPercentDen = 100;
// Pixels converted per littleCMS call: big enough to amortise the call, small enough to stay in
// cache.
constexpr std::size_t kChunk = 4096;

std::string size_text(const Image& img) {
  return std::to_string(img.width) + "x" + std::to_string(img.height);
}

// L*u*v* of the pixels of img at the indices idx, composited over black.
void to_luv(const Image& img, const std::vector<std::size_t>& idx, std::vector<double>& rgb,
            std::vector<double>& xyz, std::vector<Luv>& out) {
  const std::size_t n = idx.size();
  rgb.resize(3 * n);
  xyz.resize(3 * n);
  out.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint8_t* p = img.rgba.data() + 4 * idx[k];
    const double alpha = p[3] / kMax8;
    for (int c = 0; c < 3; ++c) rgb[3 * k + c] = p[c] / kMax8 * alpha;
  }
  srgb_to_xyz(rgb, xyz);
  for (std::size_t k = 0; k < n; ++k)
    out[k] = xyz_to_luv({xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]});
}

}  // namespace

DiffStats diff_images(const Image& a, const Image& b, Image* diff_image, const std::string& name_a,
                      const std::string& name_b) {
  if (a.width != b.width || a.height != b.height)
    throw UsageError("cannot compare images of different sizes: " + name_a + " is " + size_text(a) +
                     ", " + name_b + " is " + size_text(b));
  DiffStats s;
  s.width = a.width;
  s.height = a.height;
  s.pixels = a.pixels();
  if (diff_image) *diff_image = Image(a.width, a.height);
  const std::size_t n = std::size_t(s.pixels);
  std::vector<double> de(n, 0.0);
  std::vector<double> rgb, xyz;
  std::vector<Luv> la, lb;
  std::vector<std::size_t> idx;
  idx.reserve(kChunk);
  // Byte-identical pixels differ by exactly 0: only the others are converted (most of a
  // picture's background, and of two pictures that differ in places, costs nothing).
  const auto flush = [&] {
    to_luv(a, idx, rgb, xyz, la);
    to_luv(b, idx, rgb, xyz, lb);
    for (std::size_t k = 0; k < idx.size(); ++k) de[idx[k]] = delta_e_luv(la[k], lb[k]);
    idx.clear();
  };
  for (std::size_t k = 0; k < n; ++k) {
    if (std::memcmp(a.rgba.data() + 4 * k, b.rgba.data() + 4 * k, 4) == 0) continue;
    idx.push_back(k);
    if (idx.size() == kChunk) flush();
  }
  if (!idx.empty()) flush();
  if (n == 0) return s;
  double sum = 0;
  for (std::size_t k = 0; k < n; ++k) {
    sum += de[k];
    s.max = std::max(s.max, de[k]);
    if (diff_image) {
      std::uint8_t* q = diff_image->rgba.data() + 4 * k;
      const auto grey =
          std::uint8_t(std::lround(std::min(kMax8, de[k] * kMax8 / kDiffImageFullScale)));
      q[0] = q[1] = q[2] = grey;
      q[3] = std::uint8_t(kMax8);
    }
  }
  s.mean = sum / double(n);
  // Nearest rank: the smallest value with at least 99 % of the pixels at or below it.
  const std::size_t rank = (kPercentNum * n + kPercentDen - 1) / kPercentDen;  // ⌈0.99·n⌉ ≥ 1
  auto nth = de.begin() + std::ptrdiff_t(rank - 1);
  std::nth_element(de.begin(), nth, de.end());
  s.p99 = *nth;
  return s;
}

void to_json(nlohmann::json& j, const DiffStats& s) {
  j = {{"mean", s.mean},     {"p99", s.p99},     {"max", s.max},
       {"pixels", s.pixels}, {"width", s.width}, {"height", s.height}};
}

}  // namespace tsp

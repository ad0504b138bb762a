#include "tsp/core/color.h"

#include <lcms2.h>

#include <array>
#include <cassert>
#include <cmath>
#include <stdexcept>

namespace tsp {

namespace {

using Mat3 = std::array<double, 9>;

Mat3 invert(const Mat3& m) {
  const double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5], g = m[6], h = m[7],
               i = m[8];
  const double det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
  assert(det != 0);
  return {(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det,
          (f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det,
          (d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det};
}

// littleCMS always delivers XYZ in the ICC connection space, which is D50: it adapts sRGB's
// D65 white with the Bradford matrix stored in the profile's 'chad' tag. We undo that
// adaptation with the inverse of the same matrix, so XYZ is relative to D65 as spec §10 asks.
class SrgbConverter {
 public:
  SrgbConverter() {
    cmsHPROFILE srgb = cmsCreate_sRGBProfile();
    cmsHPROFILE xyz = cmsCreateXYZProfile();
    if (!srgb || !xyz) throw std::runtime_error("littleCMS could not create the sRGB/XYZ profiles");
    // NOCACHE makes the transform safe to share between threads; NOOPTIMIZE keeps the exact
    // matrix-shaper maths instead of a sampled lookup table.
    transform_ =
        cmsCreateTransform(srgb, TYPE_RGB_DBL, xyz, TYPE_XYZ_DBL, INTENT_RELATIVE_COLORIMETRIC,
                           cmsFLAGS_NOCACHE | cmsFLAGS_NOOPTIMIZE);
    const auto* chad = static_cast<const double*>(cmsReadTag(srgb, cmsSigChromaticAdaptationTag));
    if (!transform_ || !chad) throw std::runtime_error("littleCMS sRGB profile is incomplete");
    Mat3 m;
    for (int k = 0; k < 9; ++k) m[k] = chad[k];
    d50_to_d65_ = invert(m);
    cmsCloseProfile(srgb);
    cmsCloseProfile(xyz);
    double white_rgb[3] = {1, 1, 1}, white[3];
    convert(white_rgb, white, 1);
    white_ = {white[0], white[1], white[2]};
  }
  ~SrgbConverter() { cmsDeleteTransform(transform_); }
  SrgbConverter(const SrgbConverter&) = delete;
  SrgbConverter& operator=(const SrgbConverter&) = delete;

  void convert(const double* rgb, double* xyz, std::size_t n) const {
    cmsDoTransform(transform_, rgb, xyz, cmsUInt32Number(n));
    const Mat3& m = d50_to_d65_;
    for (std::size_t k = 0; k < n; ++k) {
      double* p = xyz + 3 * k;
      const double x = p[0], y = p[1], z = p[2];
      p[0] = m[0] * x + m[1] * y + m[2] * z;
      p[1] = m[3] * x + m[4] * y + m[5] * z;
      p[2] = m[6] * x + m[7] * y + m[8] * z;
    }
  }
  const Xyz& white() const { return white_; }

 private:
  cmsHTRANSFORM transform_ = nullptr;
  Mat3 d50_to_d65_{};
  Xyz white_;
};

const SrgbConverter& converter() {
  static const SrgbConverter c;
  return c;
}

// CIE constants for L*: ε = (6/29)³ and κ = (29/3)³.
constexpr double kEpsilon = 216.0 / 24389.0;
constexpr double kKappa = 24389.0 / 27.0;

}  // namespace

Xyz d65_white() {
  return converter().white();
}

Xyz srgb_to_xyz(double r, double g, double b) {
  double in[3] = {r, g, b}, out[3];
  converter().convert(in, out, 1);
  return {out[0], out[1], out[2]};
}

void srgb_to_xyz(std::span<const double> rgb, std::span<double> xyz) {
  assert(rgb.size() == xyz.size() && rgb.size() % 3 == 0);
  if (!rgb.empty()) converter().convert(rgb.data(), xyz.data(), rgb.size() / 3);
}

Luv xyz_to_luv(const Xyz& c) {
  const Xyz& w = converter().white();
  const double yr = c.y / w.y;
  const double l = yr > kEpsilon ? 116.0 * std::cbrt(yr) - 16.0 : kKappa * yr;
  const double den = c.x + 15.0 * c.y + 3.0 * c.z;
  if (den <= 0) return {l, 0, 0};  // black: chromaticity undefined, u* = v* = 0
  const double wden = w.x + 15.0 * w.y + 3.0 * w.z;
  const double up = 4.0 * c.x / den, vp = 9.0 * c.y / den;
  const double upn = 4.0 * w.x / wden, vpn = 9.0 * w.y / wden;
  return {l, 13.0 * l * (up - upn), 13.0 * l * (vp - vpn)};
}

Luv srgb_to_luv(double r, double g, double b) {
  return xyz_to_luv(srgb_to_xyz(r, g, b));
}

Luv srgb8_to_luv(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  constexpr double kMax8 = 255.0;
  return srgb_to_luv(r / kMax8, g / kMax8, b / kMax8);
}

double delta_e_luv(const Luv& a, const Luv& b) {
  return std::sqrt((a.l - b.l) * (a.l - b.l) + (a.u - b.u) * (a.u - b.u) +
                   (a.v - b.v) * (a.v - b.v));
}

}  // namespace tsp

#include "tsp/core/color.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace tsp {
namespace {

// The published definition of sRGB (IEC 61966-2-1, = ITU-R BT.709): chromaticities of the
// primaries and of the D65 white. The expected L*u*v* of each primary is derived from them here,
// independently of littleCMS: Y of each primary from the standard RGB→XYZ derivation (SMPTE RP 177:
// the primaries' luminances sum to the white), L* = 116·Y^(1/3) − 16, u* = 13·L*·(u′ − u′n),
// v* = 13·L*·(v′ − v′n) with u′ = 4x/(−2x + 12y + 3), v′ = 9y/(−2x + 12y + 3).
struct Chromaticity {
  double x, y;
};
constexpr Chromaticity kPrimaries[3] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
constexpr Chromaticity kD65 = {0.3127, 0.3290};
constexpr double kTolerance = 0.01;

double det3(const double m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// Luminance Y of each primary: solve Σ_k Y_k·(x_k/y_k, 1, z_k/y_k) = (X_w, 1, Z_w) by Cramer.
std::array<double, 3> primary_luminances() {
  double m[3][3], rhs[3] = {kD65.x / kD65.y, 1.0, (1 - kD65.x - kD65.y) / kD65.y};
  for (int k = 0; k < 3; ++k) {
    m[0][k] = kPrimaries[k].x / kPrimaries[k].y;
    m[1][k] = 1.0;
    m[2][k] = (1 - kPrimaries[k].x - kPrimaries[k].y) / kPrimaries[k].y;
  }
  std::array<double, 3> y;
  for (int k = 0; k < 3; ++k) {
    double mk[3][3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) mk[r][c] = c == k ? rhs[r] : m[r][c];
    y[k] = det3(mk) / det3(m);
  }
  return y;
}

Luv expected_luv(Chromaticity c, double luminance) {
  auto uv = [](Chromaticity p) {
    double den = -2 * p.x + 12 * p.y + 3;
    return std::pair{4 * p.x / den, 9 * p.y / den};
  };
  double l = 116 * std::cbrt(luminance) - 16;
  auto [u, v] = uv(c);
  auto [un, vn] = uv(kD65);
  return {l, 13 * l * (u - un), 13 * l * (v - vn)};
}

TEST(Color, SrgbPrimariesAndWhiteMatchPublishedDefinition) {
  auto lum = primary_luminances();
  // Sanity of the derivation against the published BT.709 luma coefficients.
  EXPECT_NEAR(lum[0], 0.2126, 1e-4);
  EXPECT_NEAR(lum[1], 0.7152, 1e-4);
  EXPECT_NEAR(lum[2], 0.0722, 1e-4);
  for (int k = 0; k < 3; ++k) {
    Luv want = expected_luv(kPrimaries[k], lum[k]);
    Luv got = srgb_to_luv(k == 0, k == 1, k == 2);
    EXPECT_NEAR(got.l, want.l, kTolerance) << "primary " << k;
    EXPECT_NEAR(got.u, want.u, kTolerance) << "primary " << k;
    EXPECT_NEAR(got.v, want.v, kTolerance) << "primary " << k;
  }
  Luv white = srgb_to_luv(1, 1, 1);
  EXPECT_NEAR(white.l, 100.0, kTolerance);
  EXPECT_NEAR(white.u, 0.0, kTolerance);
  EXPECT_NEAR(white.v, 0.0, kTolerance);
  Luv black = srgb_to_luv(0, 0, 0);
  EXPECT_NEAR(black.l, 0.0, kTolerance);
  // Mid grey (sRGB 0.5 → linear 0.21404) is achromatic with L* = 116·0.21404^(1/3) − 16.
  Luv grey = srgb_to_luv(0.5, 0.5, 0.5);
  EXPECT_NEAR(grey.l, 116 * std::cbrt(0.2140411) - 16, kTolerance);
  EXPECT_NEAR(grey.u, 0.0, kTolerance);
  EXPECT_NEAR(grey.v, 0.0, kTolerance);
}

TEST(Color, WhiteIsD65) {
  // D65 chromaticity x = 0.3127, y = 0.3290 (sRGB's white) → X = x/y, Z = (1−x−y)/y.
  Xyz w = d65_white();
  EXPECT_NEAR(w.y, 1.0, 1e-4);
  EXPECT_NEAR(w.x, kD65.x / kD65.y, 2e-4);
  EXPECT_NEAR(w.z, (1 - kD65.x - kD65.y) / kD65.y, 2e-4);
  // sRGB red in XYZ (IEC 61966-2-1 matrix, first column).
  Xyz red = srgb_to_xyz(1, 0, 0);
  EXPECT_NEAR(red.x, 0.4124, 2e-4);
  EXPECT_NEAR(red.y, 0.2126, 2e-4);
  EXPECT_NEAR(red.z, 0.0193, 2e-4);
}

TEST(Color, BatchMatchesSingleAndEightBitMatchesUnit) {
  std::vector<double> rgb = {0.2, 0.4, 0.6, 1, 0.5, 0, 0.05, 0.05, 0.05};
  std::vector<double> xyz(rgb.size());
  srgb_to_xyz(rgb, xyz);
  for (int k = 0; k < 3; ++k) {
    Xyz one = srgb_to_xyz(rgb[3 * k], rgb[3 * k + 1], rgb[3 * k + 2]);
    EXPECT_DOUBLE_EQ(xyz[3 * k], one.x);
    EXPECT_DOUBLE_EQ(xyz[3 * k + 1], one.y);
    EXPECT_DOUBLE_EQ(xyz[3 * k + 2], one.z);
  }
  Luv a = srgb8_to_luv(255, 0, 0), b = srgb_to_luv(1, 0, 0);
  EXPECT_DOUBLE_EQ(a.l, b.l);
  EXPECT_DOUBLE_EQ(a.u, b.u);
}

TEST(Color, DeltaEIsEuclidean) {
  EXPECT_DOUBLE_EQ(delta_e_luv({50, 3, 4}, {50, 0, 0}), 5.0);
  EXPECT_DOUBLE_EQ(delta_e_luv({10, 0, 0}, {10, 0, 0}), 0.0);
  // White against black spans the whole L* axis.
  EXPECT_NEAR(delta_e_luv(srgb_to_luv(1, 1, 1), srgb_to_luv(0, 0, 0)), 100.0, kTolerance);
}

}  // namespace
}  // namespace tsp

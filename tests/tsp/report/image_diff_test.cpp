#include "tsp/report/image_diff.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "support/reader_formula.h"
#include "tsp/core/color.h"
#include "tsp/core/error.h"

namespace {

// Independent sRGB 8-bit → L*u*v*, from published formulas: the IEC 61966-2-1 decoding, the
// sRGB→XYZ (D65) matrix as published to 7 decimals (B. Lindbloom, "RGB/XYZ Matrices"), the D65
// white as that matrix's row sums, and CIE 1976 L*u*v* with its linear segment below (6/29)³.
struct Luv3 {
  double l, u, v;
};
double decode(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
Luv3 published_luv(double r8, double g8, double b8) {
  const double r = decode(r8 / 255), g = decode(g8 / 255), b = decode(b8 / 255);
  const double x = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
  const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
  const double z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
  const double xn = 0.4124564 + 0.3575761 + 0.1804375, yn = 1.0,
               zn = 0.0193339 + 0.1191920 + 0.9503041;
  const double yr = y / yn;
  const double l =
      yr > std::pow(6.0 / 29, 3) ? 116 * std::cbrt(yr) - 16 : std::pow(29.0 / 3, 3) * yr;
  const double d = x + 15 * y + 3 * z, dn = xn + 15 * yn + 3 * zn;
  if (d == 0) return {l, 0, 0};
  return {l, 13 * l * (4 * x / d - 4 * xn / dn), 13 * l * (9 * y / d - 9 * yn / dn)};
}
double published_de(const Luv3& a, const Luv3& b) {
  return std::hypot(a.l - b.l, a.u - b.u, a.v - b.v);
}
// littleCMS stores the sRGB profile's colorants and adaptation matrix in s15.16 fixed point, so
// agreement is to about 0.01 ΔE plus 2·10⁻⁴ of the value (≈ 0.03 for ΔE ≈ 200).
constexpr double kTolerance = 0.01;
constexpr double kRelTolerance = 2e-4;
double tol(double want) {
  return kTolerance + kRelTolerance * std::abs(want);
}

tsp::Image flat(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b,
                std::uint8_t a = 255) {
  tsp::Image img(w, h);
  for (int k = 0; k < img.pixels(); ++k) {
    std::uint8_t* p = img.rgba.data() + 4 * k;
    p[0] = r, p[1] = g, p[2] = b, p[3] = a;
  }
  return img;
}

TEST(ImageDiff, IdenticalImagesDifferByZero) {
  tsp::Image a(13, 7);
  std::mt19937 rng(3);
  for (auto& v : a.rgba) v = std::uint8_t(rng());
  tsp::Image d;
  const tsp::DiffStats s = tsp::diff_images(a, a, &d);
  EXPECT_EQ(s.mean, 0);
  EXPECT_EQ(s.p99, 0);
  EXPECT_EQ(s.max, 0);
  EXPECT_EQ(s.pixels, 13 * 7);
  EXPECT_EQ(s.width, 13);
  EXPECT_EQ(s.height, 7);
  ASSERT_EQ(d.width, 13);
  for (int k = 0; k < d.pixels(); ++k) {
    EXPECT_EQ(d.rgba[4 * k], 0);
    EXPECT_EQ(d.rgba[4 * k + 3], 255);
  }
}

TEST(ImageDiff, FlatColoursMatchThePublishedLuvFormulas) {
  const std::uint8_t pairs[][6] = {{200, 30, 60, 20, 180, 90},
                                   {255, 255, 255, 0, 0, 0},
                                   {128, 128, 128, 130, 126, 129},
                                   {5, 7, 3, 0, 0, 0},  // inside L*'s linear segment
                                   {0, 0, 255, 255, 255, 0}};
  for (const auto& q : pairs) {
    const double want =
        published_de(published_luv(q[0], q[1], q[2]), published_luv(q[3], q[4], q[5]));
    const tsp::DiffStats s =
        tsp::diff_images(flat(4, 3, q[0], q[1], q[2]), flat(4, 3, q[3], q[4], q[5]));
    EXPECT_NEAR(s.mean, want, tol(want)) << int(q[0]) << "," << int(q[1]) << "," << int(q[2]);
    EXPECT_NEAR(s.p99, want, tol(want));
    EXPECT_NEAR(s.max, want, tol(want));
  }
  // White against black is exactly L* 100 − 0.
  EXPECT_NEAR(tsp::diff_images(flat(1, 1, 255, 255, 255), flat(1, 1, 0, 0, 0)).max, 100.0, 1e-6);
}

TEST(ImageDiff, AlphaIsCompositedOverBlack) {
  // Fully transparent anything equals opaque black.
  EXPECT_NEAR(tsp::diff_images(flat(2, 2, 255, 200, 10, 0), flat(2, 2, 0, 0, 0)).max, 0, 1e-9);
  // White at alpha 51/255 = 0.2 is sRGB 0.2 grey over black; against black that is L*(0.2 grey).
  const double want = published_luv(0.2 * 255, 0.2 * 255, 0.2 * 255).l;
  EXPECT_NEAR(tsp::diff_images(flat(2, 2, 255, 255, 255, 51), flat(2, 2, 0, 0, 0)).max, want,
              kTolerance);
}

TEST(ImageDiff, P99IsTheNearestRankPercentile) {
  // 200 pixels, three differ (grey 50, 100, 150 against black): ⌈0.99·200⌉ = 198th smallest is
  // the smallest of the three.
  tsp::Image a = flat(200, 1, 0, 0, 0), b = a;
  const int greys[3] = {150, 50, 100};
  for (int k = 0; k < 3; ++k) std::fill_n(b.at(17 + 60 * k, 0), 3, std::uint8_t(greys[k]));
  const double l50 = published_luv(50, 50, 50).l, l100 = published_luv(100, 100, 100).l,
               l150 = published_luv(150, 150, 150).l;
  tsp::DiffStats s = tsp::diff_images(a, b);
  EXPECT_NEAR(s.p99, l50, tol(l50));
  EXPECT_NEAR(s.max, l150, tol(l150));
  EXPECT_NEAR(s.mean, (l50 + l100 + l150) / 200, tol(l150) / 200 * 3);
  // With 100 pixels and one different, the 99th smallest is still 0.
  tsp::Image c = flat(10, 10, 0, 0, 0), d = c;
  std::fill_n(d.at(3, 4), 3, std::uint8_t(255));
  s = tsp::diff_images(c, d);
  EXPECT_EQ(s.p99, 0);
  EXPECT_NEAR(s.max, 100, 1e-6);
}

TEST(ImageDiff, StatisticsOfRandomImagesMatchABruteForceSort) {
  tsp::Image a(37, 29), b(37, 29);
  std::mt19937 rng(11);
  for (auto* img : {&a, &b})
    for (int k = 0; k < img->pixels(); ++k)
      for (int c = 0; c < 4; ++c) img->rgba[4 * k + c] = c == 3 ? 255 : std::uint8_t(rng());
  std::vector<double> de;
  for (int k = 0; k < a.pixels(); ++k) {
    const std::uint8_t *p = a.rgba.data() + 4 * k, *q = b.rgba.data() + 4 * k;
    de.push_back(published_de(published_luv(p[0], p[1], p[2]), published_luv(q[0], q[1], q[2])));
  }
  std::sort(de.begin(), de.end());
  double sum = 0;
  for (double v : de) sum += v;
  const std::size_t rank = (99 * de.size() + 99) / 100;  // ⌈0.99·n⌉
  tsp::Image img;
  const tsp::DiffStats s = tsp::diff_images(a, b, &img);
  EXPECT_NEAR(s.mean, sum / double(de.size()), tol(sum / double(de.size())));
  EXPECT_NEAR(s.p99, de[rank - 1], tol(de[rank - 1]));
  EXPECT_NEAR(s.max, de.back(), tol(de.back()));
  // The difference image: grey = min(255, round(ΔE·25.5)), opaque.
  int bad = 0;
  for (int k = 0; k < a.pixels(); ++k) {
    const std::uint8_t *p = a.rgba.data() + 4 * k, *q = b.rgba.data() + 4 * k;
    const double e = published_de(published_luv(p[0], p[1], p[2]), published_luv(q[0], q[1], q[2]));
    const double g = std::min(255.0, e * 255 / tsp::kDiffImageFullScale);
    bad += std::abs(img.rgba[4 * k] - g) > 0.5 + tol(e) * 25.5 || img.rgba[4 * k + 3] != 255 ||
           img.rgba[4 * k + 1] != img.rgba[4 * k];
  }
  EXPECT_EQ(bad, 0);
}

TEST(ImageDiff, SizeMismatchIsAUsageErrorNamingBothImagesAndSizes) {
  const std::string msg = tsptest::error_of<tsp::UsageError>(
      [] { tsp::diff_images(tsp::Image(4, 3), tsp::Image(3, 4), nullptr, "a.png", "b.png"); });
  for (const char* part : {"a.png", "b.png", "4x3", "3x4"})
    EXPECT_NE(msg.find(part), std::string::npos) << msg;
}

}  // namespace

// Colour conversions: sRGB → CIE XYZ (D65) through littleCMS 2, XYZ → CIE L*u*v*, and ΔE*uv.
// Shared by the perceptual error metric and the image difference (spec §10).
#pragma once
#include <cstdint>
#include <span>

namespace tsp {

/// CIE XYZ tristimulus values, Y of the reference white = 1.
struct Xyz {
  double x = 0, y = 0, z = 0;
};

/// CIE 1976 L*u*v* coordinates (L* in [0, 100]).
struct Luv {
  double l = 0, u = 0, v = 0;
};

/// The D65 white that sRGB (1, 1, 1) maps to, Y = 1.
Xyz d65_white();

/// Converts non-linear sRGB components in [0, 1] (IEC 61966-2-1) to XYZ relative to D65.
Xyz srgb_to_xyz(double r, double g, double b);

/// Converts many sRGB triples at once (rgb holds 3·n values in [0, 1]; xyz receives 3·n).
/// Asserts on mismatched sizes.
void srgb_to_xyz(std::span<const double> rgb, std::span<double> xyz);

/// Converts XYZ to L*u*v* with the D65 white (d65_white()).
Luv xyz_to_luv(const Xyz& xyz);

/// sRGB in [0, 1] → L*u*v* (D65).
Luv srgb_to_luv(double r, double g, double b);

/// 8-bit sRGB → L*u*v* (D65).
Luv srgb8_to_luv(std::uint8_t r, std::uint8_t g, std::uint8_t b);

/// Euclidean distance ΔE*uv between two L*u*v* colours.
double delta_e_luv(const Luv& a, const Luv& b);

}  // namespace tsp

#include "tsp/source/procedural/noise.h"

namespace tsp::noise {
namespace {

// Odd 64-bit multipliers (from the golden ratio and the murmur3 constants): any fixed odd
// constants work; these are only required never to change (kGeneratorVersion otherwise).
constexpr std::uint64_t kMulX = 0x9E3779B97F4A7C15ull;
constexpr std::uint64_t kMulY = 0xC2B2AE3D27D4EB4Full;
constexpr std::uint64_t kMulZ = 0x165667B19E3779F9ull;
constexpr std::uint64_t kMulW = 0xD6E8FEB86659FD93ull;

// murmur3's 64-bit finaliser: every input bit affects every output bit.
std::uint64_t fmix64(std::uint64_t h) {
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 33;
  h *= 0xC4CEB9FE1A85EC53ull;
  h ^= h >> 33;
  return h;
}

std::uint64_t u(std::int32_t v) {
  return std::uint64_t(std::uint32_t(v));
}

// Lattice cell of coordinate v (floor) and the fade weight inside it.
struct Cell {
  std::int32_t i;
  float f;
};
// Floor by truncation and correction: std::floor is a library call on baseline x86-64, and this
// runs once per voxel and octave. Coordinates stay far inside the int32 range.
Cell cell(double v) {
  std::int32_t i = std::int32_t(v);
  if (double(i) > v) --i;
  return {i, fade(float(v - double(i)))};
}

float lerp(float a, float b, float t) {
  return a + (b - a) * t;
}

// The 8 (y, z, w) corner hashes of one row, in the order (dy, dz, dw) = bits (0, 1, 2).
struct RowCorners {
  std::uint64_t h[8];
  float fy, fz, fw;
  RowCorners(double y, double z, double w, std::uint64_t seed) {
    Cell cy = cell(y), cz = cell(z), cw = cell(w);
    fy = cy.f;
    fz = cz.f;
    fw = cw.f;
    for (int c = 0; c < 8; ++c)
      h[c] = hash_yzw(cy.i + (c & 1), cz.i + ((c >> 1) & 1), cw.i + ((c >> 2) & 1), seed);
  }
  // Noise at lattice x = ix, blended over y, z, w: the row's value at one x lattice plane.
  float plane(std::int32_t ix) const {
    float v[8];
    for (int c = 0; c < 8; ++c) v[c] = unit_from_hash(hash_x(ix, h[c]));
    float y0 = lerp(v[0], v[1], fy), y1 = lerp(v[2], v[3], fy);
    float y2 = lerp(v[4], v[5], fy), y3 = lerp(v[6], v[7], fy);
    return lerp(lerp(y0, y1, fz), lerp(y2, y3, fz), fw);
  }
};

}  // namespace

std::uint64_t hash_yzw(std::int32_t y, std::int32_t z, std::int32_t w, std::uint64_t seed) {
  return fmix64(fmix64(seed) ^ (u(y) * kMulY) ^ (u(z) * kMulZ) ^ (u(w) * kMulW));
}

std::uint64_t hash_x(std::int32_t x, std::uint64_t yzw) {
  return fmix64(yzw ^ (u(x) * kMulX));
}

float lattice(std::int32_t x, std::int32_t y, std::int32_t z, std::int32_t w, std::uint64_t seed) {
  return unit_from_hash(hash_x(x, hash_yzw(y, z, w, seed)));
}

float value4(double x, double y, double z, double w, std::uint64_t seed) {
  RowCorners row(y, z, w, seed);
  Cell cx = cell(x);
  return lerp(row.plane(cx.i), row.plane(cx.i + 1), cx.f);
}

void add_value4_row(float* out, int n, double x0, double dx, double y, double z, double w,
                    std::uint64_t seed, float amp) {
  if (n <= 0) return;
  RowCorners row(y, z, w, seed);
  Cell first = cell(x0);
  std::int32_t cur = first.i;
  float a0 = row.plane(cur), a1 = row.plane(cur + 1);
  for (int i = 0; i < n; ++i) {
    Cell cx = cell(x0 + dx * i);
    if (cx.i != cur) {
      // Moving one cell on (the usual case) reuses the shared plane.
      a0 = (cx.i == cur + 1) ? a1 : row.plane(cx.i);
      a1 = row.plane(cx.i + 1);
      cur = cx.i;
    }
    out[i] += amp * lerp(a0, a1, cx.f);
  }
}

}  // namespace tsp::noise

// Integer-hash value noise for the built-in datasets: platform-independent, seedable, and cheap to
// evaluate along grid rows. Values depend only on the coordinates and the seed.
#pragma once
#include <cstdint>

namespace tsp::noise {

/// Hash of the lattice coordinates (y, z, w) and a seed; combine with x via hash_x().
std::uint64_t hash_yzw(std::int32_t y, std::int32_t z, std::int32_t w, std::uint64_t seed);
/// Final hash of lattice point (x, y, z, w) given hash_yzw(y, z, w, seed).
std::uint64_t hash_x(std::int32_t x, std::uint64_t yzw);
/// Lattice value in [0, 1) with 24 significant bits, from a final hash.
inline float unit_from_hash(std::uint64_t h) {
  return float(h >> 40) * (1.0f / 16777216.0f);
}
/// Value of lattice point (x, y, z, w), in [0, 1).
float lattice(std::int32_t x, std::int32_t y, std::int32_t z, std::int32_t w, std::uint64_t seed);

/// Quintic fade 6t⁵ − 15t⁴ + 10t³: C2 at lattice points, so the noise has no visible creases.
inline float fade(float t) {
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

/// 4-D value noise in [0, 1) at (x, y, z, w): lattice values blended with fade weights.
float value4(double x, double y, double z, double w, std::uint64_t seed);

/// out[i] += amp · value4(x0 + dx·i, y, z, w, seed) for i in [0, n), bit-identical to value4 but
/// with the lattice hashes shared along the row (the generator's hot loop).
void add_value4_row(float* out, int n, double x0, double dx, double y, double z, double w,
                    std::uint64_t seed, float amp);

}  // namespace tsp::noise

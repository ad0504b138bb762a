// tsp/core: what every other folder builds on (value types, errors, colour, geometry, atomic
// output, parallel_for, Stopwatch); includes nothing else of tsp/.
// Small value types shared by the whole library: grid sizes, voxel boxes, time spans, limits.
#pragma once
#include <array>
#include <cstdint>
#include <string>

namespace tsp {

/// Default leaf brick edge in samples (overlap layer included), a power of two.
inline constexpr int kDefaultBrickSize = 32;
/// Smallest and largest brick edge accepted by `build --brick`.
inline constexpr int kMinBrickSize = 4;
inline constexpr int kMaxBrickSize = 256;
/// Quantized brick samples are 16-bit: q in [0, kQuantMax].
inline constexpr int kQuantMax = 65535;

/// Size limits every input and every .tsp file is checked against before anything is allocated
/// (docs/inputs.md): the largest grid edge in samples,
inline constexpr int kMaxGridEdge = 1 << 16;
/// the most samples in one time step (16 GiB of float32),
inline constexpr std::int64_t kMaxStepSamples = std::int64_t(1) << 32;
/// the most time steps,
inline constexpr int kMaxSteps = 1 << 20;
/// the most leaf bricks,
inline constexpr std::int64_t kMaxBricks = std::int64_t(1) << 24;
/// and the most TSP nodes (octree nodes × (2T − 1)).
inline constexpr std::int64_t kMaxTspNodes = std::int64_t(1) << 28;

/// Grid size in voxels along x, y, z (x varies fastest in memory).
struct Dims {
  int x = 0, y = 0, z = 0;
  /// Number of voxels.
  std::int64_t count() const { return std::int64_t(x) * y * z; }
  /// Size along axis a (0 = x, 1 = y, 2 = z).
  int operator[](int a) const { return a == 0 ? x : (a == 1 ? y : z); }
  bool operator==(const Dims&) const = default;
};

/// Axis-aligned voxel box, half-open: [x0, x1) × [y0, y1) × [z0, z1).
struct Box {
  std::array<int, 3> lo{0, 0, 0};
  std::array<int, 3> hi{0, 0, 0};
  /// Extent along axis a.
  int size(int a) const { return hi[a] - lo[a]; }
  /// Number of voxels in the box.
  std::int64_t count() const { return std::int64_t(size(0)) * size(1) * size(2); }
  /// True when the box holds no voxel.
  bool empty() const { return size(0) <= 0 || size(1) <= 0 || size(2) <= 0; }
  bool operator==(const Box&) const = default;
};

/// Inclusive range of time steps [t0, t1].
struct Span {
  int t0 = 0, t1 = 0;
  /// Number of steps in the span.
  int length() const { return t1 - t0 + 1; }
  /// True when step t lies in the span.
  bool contains(int t) const { return t >= t0 && t <= t1; }
  bool operator==(const Span&) const = default;
};

/// Closed interval of scalar values in data units.
struct ValueRange {
  double lo = 0, hi = 0;
  /// hi − lo.
  double width() const { return hi - lo; }
  bool operator==(const ValueRange&) const = default;
};

/// "XxYxZ" for messages.
std::string to_string(const Dims& d);

/// Throws FormatError "where: …" naming what was found and the limit unless every edge of d is
/// in [1, kMaxGridEdge], d.count() ≤ kMaxStepSamples and steps is in [1, kMaxSteps]. Edges are
/// given as 64-bit values so that a file's sizes are checked before any narrowing.
void check_grid(std::int64_t x, std::int64_t y, std::int64_t z, std::int64_t steps,
                const std::string& where);

}  // namespace tsp

// The "vortex" dataset: signed compact blobs orbiting a vertical axis with differential rotation,
// each carrying a spinning three-lobed pattern. Documented in docs/datasets.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "tsp/source/procedural/noise.h"
#include "tsp/source/procedural/procedural_source.h"

namespace tsp {
namespace {

constexpr int kBlobs = 20;
constexpr double kAxisX = 0.5, kAxisY = 0.5;
constexpr double kOrbitMin = 0.06, kOrbitRange = 0.28;  // orbit radius r ∈ [0.06, 0.34)
constexpr double kTurnsAtUnitRadius = 0.12;             // turns per run = 0.12 / r: inner blobs lap
constexpr double kHeightMin = 0.25, kHeightRange = 0.5;
constexpr double kBobAmp = 0.08;  // vertical oscillation, box units
constexpr double kRadiusMin = 0.06, kRadiusRange = 0.08;
constexpr double kStretch = 2.2;  // blobs are this much longer along their orbit: arcs
constexpr double kAmpMin = 0.5, kAmpRange = 0.5;  // |amplitude|; sign alternates by hash
constexpr double kLobeDepth = 0.6;                // 3-lobed pattern modulation
constexpr double kLobeCore = 0.3;                 // lobes fade in within 0.3·radius
constexpr double kSpinTurns = 2.0;                // lobe pattern turns per run
constexpr double kTwoPi = 2.0 * std::numbers::pi;

struct Blob {
  double cx, cy, cz;  // centre
  double nx, ny;      // unit radial direction from the axis; the tangent is (−ny, nx)
  double radius, amp;
  double spin;  // lobe phase at this τ
};

// Parameter p ∈ [0,1) of blob b from the seed: one lattice value per (blob, parameter).
double param(std::uint64_t seed, int b, int p) {
  return noise::lattice(b, p, 0, 0, seed);
}

std::array<Blob, kBlobs> blobs_at(std::uint64_t seed, double tau) {
  std::array<Blob, kBlobs> out;
  for (int b = 0; b < kBlobs; ++b) {
    const double r = kOrbitMin + kOrbitRange * param(seed, b, 0);
    const double angle = kTwoPi * (param(seed, b, 1) + kTurnsAtUnitRadius / r * tau);
    const double bob = kBobAmp * std::sin(kTwoPi * (param(seed, b, 2) + (1 + b % 3) * tau));
    const double sign = param(seed, b, 5) < 0.5 ? -1.0 : 1.0;
    const double nx = std::cos(angle), ny = std::sin(angle);
    out[b] = {kAxisX + r * nx,
              kAxisY + r * ny,
              kHeightMin + kHeightRange * param(seed, b, 3) + bob,
              nx,
              ny,
              kRadiusMin + kRadiusRange * param(seed, b, 4),
              sign * (kAmpMin + kAmpRange * param(seed, b, 6)),
              kTwoPi * (param(seed, b, 7) + sign * kSpinTurns * tau)};
  }
  return out;
}

// First and one-past-last sample index on an axis of n samples whose position lies in [lo, hi].
std::pair<int, int> index_range(double lo, double hi, int n) {
  if (n == 1) return (lo <= 0.5 && 0.5 <= hi) ? std::pair{0, 1} : std::pair{0, 0};
  // One sample of slack each side: the per-voxel test decides, this only bounds the loop.
  const int a = std::max(0, int(std::ceil(lo * (n - 1))) - 1);
  const int b = std::min(n, int(std::floor(hi * (n - 1))) + 2);
  return {a, std::max(a, b)};
}

class VortexSource final : public ProceduralSource {
 public:
  using ProceduralSource::ProceduralSource;

 protected:
  void fill_slab(double tau, int z0, int z1, float* slab) const override {
    const Dims d = dims();
    std::fill(slab, slab + std::int64_t(z1 - z0) * d.y * d.x, 0.0f);
    // Blob by blob over each blob's bounding box: every voxel sums the blobs in index order,
    // whichever slab (thread) it falls in.
    for (const Blob& b : blobs_at(seed(), tau)) {
      const double reach = b.radius * kStretch;  // bounds the blob in x and y
      auto [i0, i1] = index_range(b.cx - reach, b.cx + reach, d.x);
      auto [j0, j1] = index_range(b.cy - reach, b.cy + reach, d.y);
      auto [k0, k1] = index_range(b.cz - b.radius, b.cz + b.radius, d.z);
      k0 = std::max(k0, z0);
      k1 = std::min(k1, z1);
      const double c3 = std::cos(b.spin), s3 = std::sin(b.spin);
      const double inv_r2 = 1.0 / (b.radius * b.radius);
      const double core2 = kLobeCore * kLobeCore * b.radius * b.radius;
      for (int k = k0; k < k1; ++k) {
        const double rz = normalised(k, d.z) - b.cz;
        for (int j = j0; j < j1; ++j) {
          const double ry = normalised(j, d.y) - b.cy;
          float* out = slab + (std::int64_t(k - z0) * d.y + j) * d.x;
          for (int i = i0; i < i1; ++i) {
            const double rx = normalised(i, d.x) - b.cx;
            // Blob frame: u along the orbit (shrunk by kStretch), v radial.
            const double u = (-b.ny * rx + b.nx * ry) / kStretch;
            const double v = b.nx * rx + b.ny * ry;
            const double rho2 = u * u + v * v;
            const double q2 = (rho2 + rz * rz) * inv_r2;
            if (q2 >= 1.0) continue;
            const double bump = (1.0 - q2) * (1.0 - q2) * (1.0 - q2);
            // cos(3φ − spin) with φ = atan2(v, u): Re((u + i·v)³·e^{−i·spin}) / ρ³, faded in
            // over kLobeCore·radius so the pattern is continuous on the blob's axis.
            double lobes = 0.0;
            if (rho2 > 0.0) {
              const double re3 = u * u * u - 3.0 * u * v * v;
              const double im3 = 3.0 * u * u * v - v * v * v;
              lobes = (re3 * c3 + im3 * s3) / (std::sqrt(rho2) * (rho2 + core2));
            }
            out[i] += float(b.amp * bump * (1.0 - kLobeDepth + kLobeDepth * lobes));
          }
        }
      }
    }
  }
};

}  // namespace

std::unique_ptr<GeneratedSource> make_vortex(Dims dims, int steps, std::uint64_t seed,
                                             int threads) {
  return std::make_unique<VortexSource>("vortex", dims, steps, seed, threads);
}

}  // namespace tsp

// The "shock" dataset: a curved shock front sweeping through gas, with the structure real
// simulation output has. Formulas and their purpose are documented in docs/datasets.md.
#include <algorithm>
#include <cmath>
#include <vector>

#include "tsp/source/procedural/noise.h"
#include "tsp/source/procedural/procedural_source.h"

namespace tsp {
namespace {

// Front: x_f(y, z, τ) = kFrontStart + kFrontSpeed·τ − kFrontBulge·r² + ripple, r measured from
// (kFrontCentreY, kFrontCentreZ). The front never passes kFrontStart + kFrontSpeed + ripple, so
// the gas beyond x = 0.9 is empty at every step.
constexpr double kFrontStart = 0.08;
constexpr double kFrontSpeed = 0.72;
constexpr double kFrontBulge = 0.6;
constexpr double kFrontCentreY = 0.5;
constexpr double kFrontCentreZ = 0.55;
constexpr double kRippleAmp = 0.03;  // ± on the front position
constexpr double kRippleFreq = 3.0;
constexpr double kRippleRate = 1.5;  // lattice cells per unit τ

// Gas behind the front, d = x_f − x ≥ 0 (box units).
constexpr float kShockPeak = 0.75f;  // jump at the front, decaying over kShockWidth
constexpr float kShockWidth = 0.02f;
constexpr float kPostShockFloor = 0.10f;  // compressed gas never returns to 0
constexpr float kPostShockExtra = 0.15f;  // extra compression decaying over kPostShockDecay
constexpr float kPostShockDecay = 0.30f;
constexpr float kWakeAmp = 0.75f;      // turbulence amplitude
constexpr float kWakeRise = 0.05f;     // turbulence grows over this distance behind the front
constexpr float kWakeDecay = 1.5f;     // and dies out over this one
constexpr double kWakeDrift = 0.30;    // the wake pattern advects +x at this speed (box/τ)
constexpr double kWakeStretchX = 0.6;  // eddies are longer along the flow
constexpr int kWakeOctaves = 5;
constexpr double kWakeBaseFreq = 4.0;  // octave k has 4·2^k cells per box edge
constexpr double kWakeEvolve = 1.5;    // octave k evolves (k+1)·1.5 lattice cells per unit τ
constexpr float kWakeGain = 0.5f;
constexpr double kWakeTurn = 0.7;   // octave k's lattice is turned k·0.7 rad about x
constexpr double kWakeShear = 0.4;  // and sheared along x by ±0.4 per lattice cell of y, z

// Static structures (exactly constant in time).
constexpr double kPillarX = 0.55, kPillarY = 0.42, kPillarRadius = 0.1, kPillarTop = 0.6;
constexpr float kPillarValue = 0.4f;
constexpr double kGroundBase = 0.2, kGroundRelief = 0.08;  // height = base + relief·noise
constexpr double kGroundReliefFreq = 4.0;
constexpr float kGroundValue = 0.18f, kGroundVariation = 0.12f;
constexpr double kStrataFreqXY = 10.0, kStrataFreqZ = 48.0;  // layered: fine along z

// Independent noise streams: each feature hashes with its own seed.
enum Stream : std::uint64_t { kRipple = 1, kGroundHeight, kStrata, kWake0 };
std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream) {
  return seed * 0x9E3779B97F4A7C15ull + stream * 0xBF58476D1CE4E5B9ull;
}

// exp(−dist/width) at dist = d0, d0 + step, d0 + 2·step, … (one per next() call).
class Decay {
 public:
  Decay(double d0, double width, double step)
      : value_(std::exp(-d0 / width)), factor_(std::exp(-step / width)) {}
  double next() {
    const double v = value_;
    value_ *= factor_;
    return v;
  }

 private:
  double value_, factor_;
};

class ShockSource final : public ProceduralSource {
 public:
  using ProceduralSource::ProceduralSource;

 protected:
  void fill_slab(double tau, int z0, int z1, float* slab) const override {
    const Dims d = dims();
    const double dx = d.x > 1 ? 1.0 / (d.x - 1) : 0.0;
    std::vector<double> px(d.x);
    for (int i = 0; i < d.x; ++i) px[i] = normalised(i, d.x);
    std::vector<float> row_a(d.x), row_b(d.x), turb(d.x);
    for (int k = z0; k < z1; ++k) {
      const double pz = normalised(k, d.z);
      for (int j = 0; j < d.y; ++j) {
        const double py = normalised(j, d.y);
        float* out = slab + (std::int64_t(k - z0) * d.y + j) * d.x;
        std::fill(out, out + d.x, 0.0f);
        fill_gas_row(out, px, dx, py, pz, tau, turb, row_a);
        if (pz < kGroundBase + kGroundRelief) fill_ground_row(out, d.x, dx, py, pz, row_a, row_b);
        if (pz < kPillarTop) {
          const double ry = py - kPillarY;
          for (int i = 0; i < d.x; ++i) {
            const double rx = px[i] - kPillarX;
            if (rx * rx + ry * ry < kPillarRadius * kPillarRadius) out[i] = kPillarValue;
          }
        }
      }
    }
  }

 private:
  double front_x(double py, double pz, double tau) const {
    const double ry = py - kFrontCentreY, rz = pz - kFrontCentreZ;
    const double ripple = noise::value4(py * kRippleFreq, pz * kRippleFreq, tau * kRippleRate, 0.0,
                                        stream_seed(seed(), kRipple));
    return kFrontStart + kFrontSpeed * tau - kFrontBulge * (ry * ry + rz * rz) +
           kRippleAmp * (2.0 * ripple - 1.0);
  }

  // Gas: 0 ahead of the front; shock jump, compressed gas and turbulent wake behind it.
  void fill_gas_row(float* out, const std::vector<double>& px, double dx, double py, double pz,
                    double tau, std::vector<float>& turb, std::vector<float>& tmp) const {
    const double xf = front_x(py, pz, tau);
    const int n = int(px.size());
    int behind = 0;  // voxels [0, behind) have x ≤ x_f (x grows with i)
    while (behind < n && px[behind] <= xf) ++behind;
    if (behind == 0) return;
    // Ridged turbulence: Σ gain^k·(1 − |2·noise_k − 1|)², normalised to [0, 1]: thin bright
    // filaments where a noise octave crosses its mid value, like sheared eddies.
    std::fill(turb.begin(), turb.begin() + behind, 0.0f);
    float amp = 1.0f, total = 0.0f;
    for (int o = 0; o < kWakeOctaves; ++o) {
      const double f = kWakeBaseFreq * double(1 << o);
      const double fx = f * kWakeStretchX;
      // Each octave's lattice is turned about x and sheared along x, so the octaves' lattice
      // planes do not line up into a visible grid. Neither mixes x into y or z, which keeps
      // the row evaluation valid.
      const double angle = kWakeTurn * o, c = std::cos(angle), s = std::sin(angle);
      const double ly = (c * py - s * pz) * f, lz = (s * py + c * pz) * f;
      const double shear = (o % 2 ? -kWakeShear : kWakeShear) * (ly + 0.5 * lz);
      std::fill(tmp.begin(), tmp.begin() + behind, 0.0f);
      noise::add_value4_row(tmp.data(), behind, shear - kWakeDrift * tau * fx, dx * fx, ly, lz,
                            tau * kWakeEvolve * (o + 1), stream_seed(seed(), kWake0 + o), 1.0f);
      for (int i = 0; i < behind; ++i) {
        const float ridge = 1.0f - std::fabs(2.0f * tmp[i] - 1.0f);
        turb[i] += amp * ridge * ridge;
      }
      total += amp;
      amp *= kWakeGain;
    }
    // The profiles are exponentials of dist = x_f − x: computed directly at the front voxel and
    // carried towards x = 0 by constant factors (four multiplies instead of four exp calls).
    Decay shock(xf - px[behind - 1], kShockWidth, dx),
        post(xf - px[behind - 1], kPostShockDecay, dx);
    Decay rise(xf - px[behind - 1], kWakeRise, dx), decay(xf - px[behind - 1], kWakeDecay, dx);
    const float inv_total = 1.0f / total;
    for (int i = behind - 1; i >= 0; --i) {
      const float t = turb[i] * inv_total;
      const float env = float((1.0 - rise.next()) * decay.next());
      const float v =
          float(kShockPeak * shock.next() + kPostShockFloor + kPostShockExtra * post.next()) +
          kWakeAmp * env * t * t;
      out[i] = std::min(1.0f, v);
    }
  }

  // Ground: below a noisy height field, a static layered (strata) value. No τ anywhere.
  void fill_ground_row(float* out, int n, double dx, double py, double pz,
                       std::vector<float>& height, std::vector<float>& strata) const {
    std::fill(height.begin(), height.end(), 0.0f);
    noise::add_value4_row(height.data(), n, 0.0, dx * kGroundReliefFreq, py * kGroundReliefFreq,
                          0.0, 0.0, stream_seed(seed(), kGroundHeight), 1.0f);
    std::fill(strata.begin(), strata.end(), 0.0f);
    noise::add_value4_row(strata.data(), n, 0.0, dx * kStrataFreqXY, py * kStrataFreqXY,
                          pz * kStrataFreqZ, 0.0, stream_seed(seed(), kStrata), 1.0f);
    for (int i = 0; i < n; ++i)
      if (pz < kGroundBase + kGroundRelief * height[i])
        out[i] = kGroundValue + kGroundVariation * strata[i];
  }
};

}  // namespace

std::unique_ptr<GeneratedSource> make_shock(Dims dims, int steps, std::uint64_t seed, int threads) {
  return std::make_unique<ShockSource>("shock", dims, steps, seed, threads);
}

}  // namespace tsp

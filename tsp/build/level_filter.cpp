#include "tsp/build/level_filter.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace tsp {

namespace {

// The filter taps of one output sample along an axis: voxels first … first + weights.size() − 1.
struct Taps {
  int first = 0;
  std::vector<float> weights;
};

// Taps of the m samples origin + j·f (clamped to the last voxel n − 1) along an axis of n voxels.
std::vector<Taps> axis_taps(int origin, int f, int m, int n) {
  std::vector<Taps> taps(static_cast<std::size_t>(m));
  for (int j = 0; j < m; ++j) {
    const int p = std::min(origin + j * f, n - 1);
    const int r = std::min({f / 2, p, n - 1 - p});
    Taps& t = taps[std::size_t(j)];
    t.first = p - r;
    if (r == 0) {
      t.weights = {1.f};
      continue;
    }
    t.weights.assign(std::size_t(2 * r + 1), 1.f);
    t.weights.front() = t.weights.back() = 0.5f;
  }
  return taps;
}

float clamp_value(float v, const std::optional<ValueRange>& c) {
  if (!c || !std::isfinite(v)) return v;
  return std::clamp(v, float(c->lo), float(c->hi));
}

// One separable pass along the middle axis of in, laid out [outer][len][inner] with the middle
// axis starting at voxel in_lo; out gets [outer][taps.size()][inner]. Non-finite inputs are left
// out and the weights renormalised.
void pass(const float* in, int outer, int len, int inner, int in_lo, const std::vector<Taps>& taps,
          float* out) {
  const int m = int(taps.size());
  for (int o = 0; o < outer; ++o)
    for (int j = 0; j < m; ++j) {
      const Taps& t = taps[std::size_t(j)];
      float* dst = out + (std::size_t(o) * m + j) * inner;
      for (int i = 0; i < inner; ++i) {
        double sum = 0, wsum = 0;
        for (std::size_t k = 0; k < t.weights.size(); ++k) {
          const float v = in[(std::size_t(o) * len + (t.first - in_lo + int(k))) * inner + i];
          if (!std::isfinite(v)) continue;
          sum += double(t.weights[k]) * v;
          wsum += t.weights[k];
        }
        dst[i] = wsum > 0 ? float(sum / wsum) : std::nanf("");
      }
    }
}

}  // namespace

void filter_level(std::span<const float> vol, Dims d, const BrickLattice& l,
                  const std::optional<ValueRange>& clamp, LevelFilterScratch& s,
                  std::vector<float>& out) {
  assert(std::int64_t(vol.size()) == d.count());
  std::array<std::vector<Taps>, 3> taps;
  std::array<int, 3> lo{}, len{};
  for (int a = 0; a < 3; ++a) {
    taps[a] = axis_taps(l.origin[a], l.factor[a], l.samples[a], d[a]);
    lo[a] = taps[a].front().first;
    const Taps& last = taps[a].back();
    len[a] = last.first + int(last.weights.size()) - lo[a];
  }
  // The window, copied (and clamped) as [z][y][x].
  s.a.resize(std::size_t(len[0]) * len[1] * len[2]);
  for (int z = 0; z < len[2]; ++z)
    for (int y = 0; y < len[1]; ++y) {
      const float* src =
          vol.data() + lo[0] + std::int64_t(d.x) * ((lo[1] + y) + std::int64_t(d.y) * (lo[2] + z));
      float* dst = s.a.data() + (std::size_t(z) * len[1] + y) * len[0];
      for (int x = 0; x < len[0]; ++x) dst[x] = clamp_value(src[x], clamp);
    }
  const int mx = l.samples[0], my = l.samples[1];
  s.b.resize(std::size_t(len[2]) * len[1] * mx);
  pass(s.a.data(), len[2] * len[1], len[0], 1, lo[0], taps[0], s.b.data());  // x
  s.a.resize(std::size_t(len[2]) * my * mx);
  pass(s.b.data(), len[2], len[1], mx, lo[1], taps[1], s.a.data());  // y
  out.resize(std::size_t(l.count()));
  pass(s.a.data(), 1, len[2], my * mx, lo[2], taps[2], out.data());  // z
}

double level_residual(std::span<const float> vol, Dims d, const BrickLattice& l, const Box& own,
                      std::span<const float> level, const std::optional<ValueRange>& clamp) {
  assert(std::int64_t(level.size()) == l.count());
  const int mx = l.samples[0], my = l.samples[1];
  // Per axis, each voxel's lower lattice sample and its weight towards the next one.
  std::array<std::vector<int>, 3> i0;
  std::array<std::vector<float>, 3> w;
  for (int a = 0; a < 3; ++a) {
    for (int v = own.lo[a]; v < own.hi[a]; ++v) {
      const double u = double(v - l.origin[a]) / l.factor[a];
      int k = std::clamp(int(std::floor(u)), 0, std::max(0, l.samples[a] - 2));
      float t = l.samples[a] > 1 ? float(std::clamp(u - k, 0.0, 1.0)) : 0.f;
      i0[a].push_back(k);
      w[a].push_back(t);
    }
  }
  auto at = [&](int x, int y, int z) {
    return double(level[(std::size_t(z) * my + y) * mx + x]);
  };
  double sum = 0;
  std::int64_t n = 0;
  for (int z = own.lo[2]; z < own.hi[2]; ++z) {
    const int kz = i0[2][std::size_t(z - own.lo[2])], kz1 = std::min(kz + 1, l.samples[2] - 1);
    const double tz = w[2][std::size_t(z - own.lo[2])];
    for (int y = own.lo[1]; y < own.hi[1]; ++y) {
      const int ky = i0[1][std::size_t(y - own.lo[1])], ky1 = std::min(ky + 1, my - 1);
      const double ty = w[1][std::size_t(y - own.lo[1])];
      const float* row = vol.data() + std::int64_t(d.x) * (y + std::int64_t(d.y) * z);
      for (int x = own.lo[0]; x < own.hi[0]; ++x) {
        const float v = clamp_value(row[x], clamp);
        if (!std::isfinite(v)) continue;
        const int kx = i0[0][std::size_t(x - own.lo[0])], kx1 = std::min(kx + 1, mx - 1);
        const double tx = w[0][std::size_t(x - own.lo[0])];
        auto lerp = [](double p, double q, double t) { return p + (q - p) * t; };
        const double r = lerp(lerp(lerp(at(kx, ky, kz), at(kx1, ky, kz), tx),
                                   lerp(at(kx, ky1, kz), at(kx1, ky1, kz), tx), ty),
                              lerp(lerp(at(kx, ky, kz1), at(kx1, ky, kz1), tx),
                                   lerp(at(kx, ky1, kz1), at(kx1, ky1, kz1), tx), ty),
                              tz);
        if (!std::isfinite(r)) continue;
        sum += (r - v) * (r - v);
        ++n;
      }
    }
  }
  return n > 0 ? std::sqrt(sum / double(n)) : 0.0;
}

}  // namespace tsp

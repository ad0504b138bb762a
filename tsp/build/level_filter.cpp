#include "tsp/build/level_filter.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>

namespace tsp {

namespace {

using Taps = detail::FilterTaps;

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
void pass(const float* in, int outer, int len, int inner, int in_lo, std::span<const Taps> taps,
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

// Per voxel of own along axis a, its lower lattice sample k and its weight t towards k + 1.
void residual_weights(const BrickLattice& l, const Box& own, int a, std::vector<int>& k0,
                      std::vector<float>& w) {
  k0.clear();
  w.clear();
  for (int v = own.lo[a]; v < own.hi[a]; ++v) {
    const double u = double(v - l.origin[a]) / l.factor[a];
    const int k = std::clamp(int(std::floor(u)), 0, std::max(0, l.samples[a] - 2));
    k0.push_back(k);
    w.push_back(l.samples[a] > 1 ? float(std::clamp(u - k, 0.0, 1.0)) : 0.f);
  }
}

// Adds plane z of own's squared differences between plane (d.x · d.y floats) and the trilinear
// reconstruction from level to sum, and their count to n, in y then x order.
void residual_plane(const float* plane, Dims d, const BrickLattice& l, const Box& own, int z,
                    const std::vector<int> (&k0)[3], const std::vector<float> (&w)[3],
                    std::span<const float> level, const std::optional<ValueRange>& clamp,
                    double& sum, std::int64_t& n) {
  const int mx = l.samples[0], my = l.samples[1];
  auto at = [&](int x, int y, int z) {
    return double(level[(std::size_t(z) * my + y) * mx + x]);
  };
  const int kz = k0[2][std::size_t(z - own.lo[2])], kz1 = std::min(kz + 1, l.samples[2] - 1);
  const double tz = w[2][std::size_t(z - own.lo[2])];
  for (int y = own.lo[1]; y < own.hi[1]; ++y) {
    const int ky = k0[1][std::size_t(y - own.lo[1])], ky1 = std::min(ky + 1, my - 1);
    const double ty = w[1][std::size_t(y - own.lo[1])];
    const float* row = plane + std::int64_t(d.x) * y;
    for (int x = own.lo[0]; x < own.hi[0]; ++x) {
      const float v = clamp_value(row[x], clamp);
      if (!std::isfinite(v)) continue;
      const int kx = k0[0][std::size_t(x - own.lo[0])], kx1 = std::min(kx + 1, mx - 1);
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

}  // namespace

LevelStream::LevelStream(Dims d, const BrickLattice& l, std::optional<Box> own,
                         std::optional<ValueRange> clamp)
    : dims_(d), lattice_(l), own_(own), clamp_(clamp) {
  for (int a = 0; a < 3; ++a) {
    taps_[a] = axis_taps(l.origin[a], l.factor[a], l.samples[a], d[a]);
    lo_[a] = taps_[a].front().first;
    len_[a] = taps_[a].back().first + int(taps_[a].back().weights.size()) - lo_[a];
    if (own_) residual_weights(l, *own_, a, res_k_[a], res_t_[a]);
  }
  restart();
}

void LevelStream::restart() {
  next_reduce_ = reduced_lo_ = lo_[2];
  next_sample_ = 0;
  next_residual_ = own_ ? own_->lo[2] : dims_.z;
  if (own_ && own_->empty()) next_residual_ = dims_.z;
  sum_ = 0;
  count_ = 0;
  reduced_.clear();
}

int LevelStream::needs_from() const {
  int z = dims_.z;
  if (next_sample_ < lattice_.samples[2]) z = std::min(z, next_reduce_);
  if (own_ && next_residual_ < own_->hi[2]) z = std::min(z, next_residual_);
  return z;
}

void LevelStream::release() {
  std::vector<float>().swap(out_);
  std::vector<float>().swap(reduced_);
}

double LevelStream::residual() const {
  return count_ > 0 ? std::sqrt(sum_ / double(count_)) : 0.0;
}

// The window of plane z, copied (and clamped) as [y][x], then filtered along x and y: one plane
// of [my][mx] appended to reduced_.
void LevelStream::reduce_plane(const float* plane) {
  const int mx = lattice_.samples[0], my = lattice_.samples[1];
  a_.resize(std::size_t(len_[1]) * len_[0]);
  for (int y = 0; y < len_[1]; ++y) {
    const float* src = plane + lo_[0] + std::int64_t(dims_.x) * (lo_[1] + y);
    float* dst = a_.data() + std::size_t(y) * len_[0];
    for (int x = 0; x < len_[0]; ++x) dst[x] = clamp_value(src[x], clamp_);
  }
  b_.resize(std::size_t(len_[1]) * mx);
  pass(a_.data(), len_[1], len_[0], 1, lo_[0], taps_[0], b_.data());  // x
  const std::size_t at = reduced_.size();
  reduced_.resize(at + std::size_t(my) * mx);
  pass(b_.data(), 1, len_[1], mx, lo_[1], taps_[1], reduced_.data() + at);  // y
}

void LevelStream::feed(const PlaneFn& plane, int end) {
  const int mz = lattice_.samples[2];
  const std::size_t inner = std::size_t(lattice_.samples[0]) * lattice_.samples[1];
  if (out_.empty()) out_.resize(std::size_t(lattice_.count()));
  const int reduce_end = std::min(end, lo_[2] + len_[2]);
  for (; next_reduce_ < reduce_end && next_sample_ < mz; ++next_reduce_)
    reduce_plane(plane(next_reduce_));
  // z: each sample whose window is reduced.
  for (; next_sample_ < mz; ++next_sample_) {
    const Taps& t = taps_[2][std::size_t(next_sample_)];
    if (t.first + int(t.weights.size()) > next_reduce_) break;
    pass(reduced_.data(), 1, next_reduce_ - reduced_lo_, int(inner), reduced_lo_,
         std::span(&t, 1), out_.data() + std::size_t(next_sample_) * inner);
  }
  // Reduced planes below the next sample's window are not needed again.
  const int keep = next_sample_ < mz
                       ? std::min(taps_[2][std::size_t(next_sample_)].first, next_reduce_)
                       : next_reduce_;
  if (keep > reduced_lo_) {
    const std::size_t drop = std::size_t(keep - reduced_lo_) * inner;
    reduced_.erase(reduced_.begin(), reduced_.begin() + std::ptrdiff_t(drop));
    reduced_lo_ = keep;
  }
  // The residual of each plane of own whose two lattice layers are computed.
  if (!own_) return;
  for (; next_residual_ < std::min(end, own_->hi[2]); ++next_residual_) {
    const int kz = res_k_[2][std::size_t(next_residual_ - own_->lo[2])];
    if (std::min(kz + 1, mz - 1) >= next_sample_) break;
    residual_plane(plane(next_residual_), dims_, lattice_, *own_, next_residual_, res_k_, res_t_,
                   out_, clamp_, sum_, count_);
  }
}

void filter_level(std::span<const float> vol, Dims d, const BrickLattice& l,
                  const std::optional<ValueRange>& clamp, std::vector<float>& out) {
  assert(std::int64_t(vol.size()) == d.count());
  LevelStream s(d, l, std::nullopt, clamp);
  s.feed([&](int z) { return vol.data() + std::int64_t(d.x) * d.y * z; }, d.z);
  assert(s.done());
  out = s.samples();
}

double level_residual(std::span<const float> vol, Dims d, const BrickLattice& l, const Box& own,
                      std::span<const float> level, const std::optional<ValueRange>& clamp) {
  assert(std::int64_t(level.size()) == l.count());
  std::vector<int> k0[3];
  std::vector<float> w[3];
  for (int a = 0; a < 3; ++a) residual_weights(l, own, a, k0[a], w[a]);
  double sum = 0;
  std::int64_t n = 0;
  for (int z = own.lo[2]; z < own.hi[2]; ++z)
    residual_plane(vol.data() + std::int64_t(d.x) * d.y * z, d, l, own, z, k0, w, level, clamp,
                   sum, n);
  return n > 0 ? std::sqrt(sum / double(n)) : 0.0;
}

}  // namespace tsp

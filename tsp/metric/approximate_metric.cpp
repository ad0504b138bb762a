#include "tsp/metric/approximate_metric.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "tsp/core/color.h"

namespace tsp {

namespace {
// The perceptual metric scales ΔE*uv into [0, 1]-like units, as colours are in eq. 7 (spec §4).
constexpr double kLuvScale = 100.0;

// Eq. 7: α1·|rgb1 − rgb2|² + (α1 − α2)², on any three colour coordinates.
inline double distance(const double* c1, const double* c2) {
  const double d0 = c1[0] - c2[0], d1 = c1[1] - c2[1], d2 = c1[2] - c2[2], da = c1[3] - c2[3];
  return c1[3] * (d0 * d0 + d1 * d1 + d2 * d2) + da * da;
}
}  // namespace

ApproximateMetric::ApproximateMetric(Metric metric, const TransferFunction& tf)
    : metric_(metric), version_(tf.version()), domain_(tf.domain()) {
  assert(metric != Metric::reference);
  const int k = tf.size();
  entries_.resize(k);
  opaque_prefix_.assign(k + 1, 0);
  std::vector<double> rgb(3 * std::size_t(k)), xyz(3 * std::size_t(k));
  for (int j = 0; j < k; ++j) {
    const Rgba& c = tf.entry(j);
    Entry& e = entries_[j];
    e.rgb[0] = rgb[3 * j] = c.r;
    e.rgb[1] = rgb[3 * j + 1] = c.g;
    e.rgb[2] = rgb[3 * j + 2] = c.b;
    e.c[0] = c.r;
    e.c[1] = c.g;
    e.c[2] = c.b;
    e.c[3] = c.a;
    opaque_prefix_[j + 1] = opaque_prefix_[j] + (c.a > 0);
  }
  if (metric == Metric::perceptual) {
    srgb_to_xyz(rgb, xyz);
    for (int j = 0; j < k; ++j) {
      const Luv luv = xyz_to_luv({xyz[3 * j], xyz[3 * j + 1], xyz[3 * j + 2]});
      entries_[j].c[0] = luv.l / kLuvScale;
      entries_[j].c[1] = luv.u / kLuvScale;
      entries_[j].c[2] = luv.v / kLuvScale;
    }
  }
  step_distance_.resize(k - 1);
  double sum = 0;
  for (int j = 0; j + 1 < k; ++j)
    sum += step_distance_[j] = distance(entries_[j].c, entries_[j + 1].c);
  variation_ = std::sqrt(sum);
}

EntryRange ApproximateMetric::entry_range(const NodeStats& stats) const {
  const int k = int(entries_.size());
  auto entry_of = [&](double v) {
    const double f = (v - domain_.lo) / (domain_.hi - domain_.lo) * k;
    if (!(f > 0)) return 0;
    return f >= k ? k - 1 : int(f);
  };
  return {entry_of(stats.min), entry_of(stats.max)};
}

NodeResult ApproximateMetric::evaluate(const NodeStats& stats) const {
  NodeResult out;
  if (stats.empty()) {  // wholly outside a stencil
    out.transparent = true;
    return out;
  }
  const EntryRange r = entry_range(stats);
  const int lo = r.lo, hi = std::max(r.lo, r.hi);
  if (opaque_prefix_[hi + 1] == opaque_prefix_[lo]) {
    out.transparent = true;  // spec §3: exact, from min/max; errors 0 so the node is coherent
    return out;
  }
  const int k = int(entries_.size());
  const double width = (domain_.hi - domain_.lo) / k;
  const double mean = stats.mean, sigma = stats.std;

  // Population estimate p(j) (eq. 14), scaled so that the entry holding the mean has p = 1.
  // Successive ratios of a Gaussian sampled at equal steps shrink by q = exp(−w²/σ²), so two
  // multiplications per entry replace an exp() and nothing overflows (every ratio is ≤ 1).
  thread_local std::vector<double> p;
  p.assign(hi - lo + 1, 0.0);
  double* const pw = p.data() - lo;  // pw[j] for j in [lo, hi]
  const int jc = std::clamp(int(std::floor((mean - domain_.lo) / width)), lo, hi);
  pw[jc] = 1;
  const double inv2s2 = 1.0 / (2.0 * sigma * sigma);
  if (sigma > 0 && std::isfinite(inv2s2)) {
    const double d = domain_.lo + (jc + 0.5) * width - mean;  // x(jc) − v̄
    const double q = std::exp(-width * width * 2.0 * inv2s2);
    double pj = 1, ratio = std::exp(-(2.0 * d * width + width * width) * inv2s2);
    for (int j = jc + 1; j <= hi; ++j, ratio *= q) pw[j] = pj *= ratio;
    pj = 1;
    ratio = std::exp(-(-2.0 * d * width + width * width) * inv2s2);
    for (int j = jc - 1; j >= lo; --j, ratio *= q) pw[j] = pj *= ratio;
  }  // σ = 0 (or so small that σ² underflows): all weight on the entry holding v̄

  // Eqs. 15–16: estimated mean colour. Scalar accumulators keep the sums in registers.
  const double* w = p.data() - lo;
  double ptot = 0, c0 = 0, c1 = 0, c2 = 0, c3 = 0;
  for (int j = lo; j <= hi; ++j) {
    const double* e = entries_[j].c;
    ptot += w[j];
    c0 += w[j] * e[0];
    c1 += w[j] * e[1];
    c2 += w[j] * e[2];
    c3 += w[j] * e[3];
  }
  const double c[4] = {c0 / ptot, c1 / ptot, c2 / ptot, c3 / ptot};
  double rgb[3] = {c[0], c[1], c[2]};
  if (metric_ == Metric::perceptual) {  // d() works in L*u*v*; the reported colour stays sRGB
    double r = 0, g = 0, b = 0;
    for (int j = lo; j <= hi; ++j) {
      const double* e = entries_[j].rgb;
      r += w[j] * e[0];
      g += w[j] * e[1];
      b += w[j] * e[2];
    }
    rgb[0] = r / ptot, rgb[1] = g / ptot, rgb[2] = b / ptot;
  }
  out.mean = {float(rgb[0]), float(rgb[1]), float(rgb[2]), float(c[3])};
  if (metric_ == Metric::scalar) {
    out.spatial = stats.spatial_error;
    out.temporal = stats.temporal_error;
    return out;
  }

  // Eqs. 17–19: f̃ = sqrt(d(ĉ, 0)), σ̃ = sqrt(Σ p/p_tot · d(c(j), ĉ)), e_s = σ̃ / f̃.
  const double f2 = c[3] * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) + c[3] * c[3];
  double dev = 0, local_variation = 0;
  for (int j = lo; j <= hi; ++j) dev += w[j] * distance(entries_[j].c, c);
  const double f = std::sqrt(f2);
  out.spatial = f > 0 ? float(std::sqrt(dev / ptot) / f) : 0.0f;
  if (metric_ == Metric::approximate) {
    out.temporal = float(stats.temporal_error * variation_);  // eq. 20
  } else {
    // Perceptual: V restricted to [j_min, j_max], each step weighted by the mean population
    // estimate of its two entries (peak weight 1), so a node only feels the part of the TF its
    // values can reach.
    for (int j = lo; j < hi; ++j) local_variation += 0.5 * (w[j] + w[j + 1]) * step_distance_[j];
    out.temporal = float(stats.temporal_error * std::sqrt(local_variation));
  }
  return out;
}

}  // namespace tsp

#include "player/tf_handles.h"

#include <algorithm>
#include <cmath>

#include "tsp/core/error.h"

namespace tspplayer {

namespace {

constexpr float kKnotEpsilon = 1e-4f;  // slope change that marks a TF knot

tsp::Rgba mix(const tsp::Rgba& a, const tsp::Rgba& b, double t) {
  const float u = float(t);
  return {a.r + (b.r - a.r) * u, a.g + (b.g - a.g) * u, a.b + (b.b - a.b) * u,
          a.a + (b.a - a.a) * u};
}

tsp::Rgba minus(const tsp::Rgba& a, const tsp::Rgba& b) {
  return {a.r - b.r, a.g - b.g, a.b - b.b, a.a - b.a};
}

tsp::Rgba plus_clamped(const tsp::Rgba& a, const tsp::Rgba& b) {
  auto c = [](float v) { return std::clamp(v, 0.f, 1.f); };
  return {c(a.r + b.r), c(a.g + b.g), c(a.b + b.b), c(a.a + b.a)};
}

// The TF's knots: the first and last entries and every entry where the table's slope changes.
// A knot between two entry centres bends the table at both: each run of bending entries is one
// knot, placed mid-run (a 5-point file shows 5 handles, not 8).
std::vector<tsp::TfPoint> knots(const tsp::TransferFunction& tf) {
  const int n = tf.size();
  std::vector<tsp::TfPoint> pts;
  auto slope_changes = [&tf](int j) {
    const tsp::Rgba a = tf.entry(j - 1), b = tf.entry(j), c = tf.entry(j + 1);
    const float d[4] = {(c.r - b.r) - (b.r - a.r), (c.g - b.g) - (b.g - a.g),
                        (c.b - b.b) - (b.b - a.b), (c.a - b.a) - (b.a - a.a)};
    for (float v : d)
      if (std::fabs(v) > kKnotEpsilon) return true;
    return false;
  };
  for (int j = 0; j < n; ++j) {
    if (j == 0 || j == n - 1) {
      pts.push_back({tf.entry_value(j), tf.entry(j)});
      continue;
    }
    if (!slope_changes(j)) continue;
    int last = j;
    while (last + 1 < n - 1 && slope_changes(last + 1)) ++last;
    const double x = 0.5 * (tf.entry_value(j) + tf.entry_value(last));
    pts.push_back({x, sample_tf(tf, x)});
    j = last;
  }
  return pts;
}

}  // namespace

tsp::Rgba sample_tf(const tsp::TransferFunction& tf, double v) {
  const tsp::ValueRange d = tf.domain();
  const int n = tf.size();
  const double span = d.hi > d.lo ? d.hi - d.lo : 1.0;
  double f = std::clamp((v - d.lo) / span * n - 0.5, 0.0, double(n - 1));
  if (std::fabs(f - std::round(f)) < 1e-9) f = std::round(f);  // an entry's centre: the entry
  const int j = std::min(n - 1, int(std::floor(f)));
  return j + 1 < n ? mix(tf.entry(j), tf.entry(j + 1), f - j) : tf.entry(j);
}

TfHandles rescale_handles(std::span<const tsp::TfPoint> points, tsp::ValueRange from,
                          const tsp::TransferFunction& tf) {
  const tsp::ValueRange to = tf.domain();
  TfHandles h{tf, {points.begin(), points.end()}};
  for (tsp::TfPoint& p : h.placed) {
    const double u = (p.x - from.lo) / (from.hi - from.lo);
    p.x = u <= 0 ? to.lo : u >= 1 ? to.hi : to.lo + u * (to.hi - to.lo);  // (ends exact)
  }
  return h;
}

TfHandles place_handles(const tsp::TransferFunction& tf) {
  TfHandles h{tf, knots(tf)};
  if (int(h.placed.size()) <= kMaxKnotHandles) return h;
  h.placed.clear();
  const tsp::ValueRange d = tf.domain();
  for (int i = 0; i < kSampledHandles; ++i) {
    const double x = d.lo + (d.hi - d.lo) * i / (kSampledHandles - 1);
    h.placed.push_back({x, sample_tf(tf, x)});
  }
  return h;
}

tsp::TransferFunction warp_handles(const TfHandles& h, std::span<const tsp::TfPoint> moved) {
  const std::size_t n = h.placed.size();
  if (moved.size() != n || n == 0)
    throw tsp::UsageError("transfer function editor: " + std::to_string(moved.size()) +
                          " handles for " + std::to_string(n));
  if (std::equal(moved.begin(), moved.end(), h.placed.begin(),
                 [](const tsp::TfPoint& a, const tsp::TfPoint& b) { return a.x == b.x && a.c == b.c; }))
    return h.base;
  std::vector<tsp::Rgba> delta(n);
  for (std::size_t k = 0; k < n; ++k) delta[k] = minus(moved[k].c, h.placed[k].c);
  const tsp::ValueRange d = h.base.domain();
  tsp::TransferFunction out(d, h.base.size());
  std::vector<tsp::Rgba> colours(std::size_t(h.base.size()));
  // Where value v of the result comes from in the base (u) and the change there.
  for (int j = 0; j < h.base.size(); ++j) {
    const double v = out.entry_value(j);
    double u;
    tsp::Rgba change;
    if (v <= moved[0].x) {  // [d.lo, first] stretched onto [d.lo, first placed]
      const double w = moved[0].x - d.lo;
      u = w > 0 ? d.lo + (v - d.lo) / w * (h.placed[0].x - d.lo) : h.placed[0].x;
      change = delta[0];
    } else if (v >= moved[n - 1].x) {  // [last, d.hi] onto [last placed, d.hi]
      const double w = d.hi - moved[n - 1].x;
      u = w > 0 ? h.placed[n - 1].x + (v - moved[n - 1].x) / w * (d.hi - h.placed[n - 1].x)
                : h.placed[n - 1].x;
      change = delta[n - 1];
    } else {
      std::size_t k = 0;
      while (k + 2 < n && moved[k + 1].x < v) ++k;
      const double w = moved[k + 1].x - moved[k].x;
      const double t = w > 0 ? (v - moved[k].x) / w : 1.0;
      u = h.placed[k].x + t * (h.placed[k + 1].x - h.placed[k].x);
      change = mix(delta[k], delta[k + 1], t);
    }
    colours[std::size_t(j)] = plus_clamped(sample_tf(h.base, u), change);
  }
  out.set_entries(0, colours);
  return out;
}

double clamp_handle_x(std::span<const tsp::TfPoint> points, int i, double x) {
  const std::size_t k = std::size_t(i);
  const double lo = k > 0 ? points[k - 1].x : -INFINITY;
  const double hi = k + 1 < points.size() ? points[k + 1].x : INFINITY;
  return std::clamp(x, lo, std::max(lo, hi));
}

int add_handle(TfHandles& h, std::vector<tsp::TfPoint>& points,
               const tsp::TransferFunction& current, double x, tsp::Rgba c) {
  h.base = current;
  h.placed = points;
  const tsp::TfPoint here{x, sample_tf(current, x)};
  const auto at = std::upper_bound(h.placed.begin(), h.placed.end(), x,
                                   [](double v, const tsp::TfPoint& p) { return v < p.x; });
  const int index = int(at - h.placed.begin());
  h.placed.insert(at, here);
  points = h.placed;
  points[std::size_t(index)].c = c;
  return index;
}

tsp::TransferFunction remove_handle(TfHandles& h, std::vector<tsp::TfPoint>& points,
                                    const tsp::TransferFunction& current, int i) {
  if (points.size() < 3 || i < 0 || i >= int(points.size())) return current;
  const std::size_t k = std::size_t(i);
  const bool first = k == 0, last = k + 1 == points.size();
  const double lo = first ? -INFINITY : points[k - 1].x, hi = last ? INFINITY : points[k + 1].x;
  const tsp::Rgba a = first ? points[k + 1].c : points[k - 1].c;
  const tsp::Rgba b = last ? points[k - 1].c : points[k + 1].c;
  std::vector<tsp::Rgba> colours(current.entries().begin(), current.entries().end());
  for (int j = 0; j < current.size(); ++j) {
    const double v = current.entry_value(j);
    if (v <= lo || v >= hi) continue;
    colours[std::size_t(j)] =
        first || last ? (first ? a : b) : mix(a, b, (v - lo) / std::max(hi - lo, 1e-300));
  }
  tsp::TransferFunction out(current.domain(), current.size());
  out.set_entries(0, colours);
  points.erase(points.begin() + i);
  h.base = out;
  h.placed = points;
  return out;
}

}  // namespace tspplayer

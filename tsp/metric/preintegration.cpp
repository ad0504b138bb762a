#include "tsp/metric/preintegration.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "tsp/core/parallel_for.h"

namespace tsp {

namespace {

// Largest opacity per voxel used, so that ln(1 − α) stays finite.
constexpr double kMaxAlpha = 1 - 1e-9;

struct Bin {
  double r, g, b, log_t;  // colour and ln(1 − α) per voxel
};

std::vector<Bin> bins_of(const TransferFunction& tf) {
  std::vector<Bin> out;
  out.reserve(std::size_t(tf.size()));
  for (const Rgba& e : tf.entries())
    out.push_back({e.r, e.g, e.b, std::log1p(-std::clamp(double(e.a), 0.0, kMaxAlpha))});
  return out;
}

Rgba integrate(const std::vector<Bin>& bins, double uf, double ub, double length) {
  const int k = int(bins.size());
  auto bin_of = [&](double u) { return std::clamp(int(std::floor(u * k)), 0, k - 1); };
  double cr = 0, cg = 0, cb = 0, t = 1;
  auto add = [&](const Bin& b, double len) {
    const double tb = std::exp(b.log_t * len);
    const double a = t * (1 - tb);
    cr += a * b.r;
    cg += a * b.g;
    cb += a * b.b;
    t *= tb;
  };
  const int first = bin_of(uf), last = bin_of(ub);
  const double du = std::abs(ub - uf);
  if (first == last || du <= 0) {
    add(bins[std::size_t(first)], length);
  } else {
    const int dir = last > first ? 1 : -1;
    double u = uf;
    for (int j = first;; j += dir) {
      // Where the ramp leaves bin j (its far boundary in the ramp's direction), or its end.
      const double edge = j == last ? ub : double(dir > 0 ? j + 1 : j) / k;
      add(bins[std::size_t(j)], length * std::abs(edge - u) / du);
      u = edge;
      if (j == last) break;
    }
  }
  return {float(cr), float(cg), float(cb), float(1 - t)};
}

}  // namespace

Rgba integrate_segment(const TransferFunction& tf, double u_front, double u_back, double length) {
  assert(length > 0);
  return integrate(bins_of(tf), std::clamp(u_front, 0.0, 1.0), std::clamp(u_back, 0.0, 1.0),
                   length);
}

std::vector<Rgba> preintegrate(const TransferFunction& tf, double length, int threads) {
  assert(length > 0);
  const std::vector<Bin> bins = bins_of(tf);
  const int k = int(bins.size());
  std::vector<Rgba> table(std::size_t(k) * std::size_t(k));
  parallel_for(k, 8, threads, [&](int, std::int64_t begin, std::int64_t end) {
    for (std::int64_t b = begin; b < end; ++b)
      for (int f = 0; f < k; ++f)
        table[std::size_t(f) + std::size_t(k) * std::size_t(b)] =
            integrate(bins, (f + 0.5) / k, (double(b) + 0.5) / k, length);
  });
  return table;
}

}  // namespace tsp

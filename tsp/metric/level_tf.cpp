#include "tsp/metric/level_tf.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace tsp {

namespace {
// Entries beyond this many σ from the centre carry no weight worth adding (e^(−4.5) ≈ 1 %).
constexpr double kKernelSigmas = 3;
}  // namespace

double level_tf_sigma(int row) {
  assert(row >= 0 && row < kLevelTfRows);
  if (row == 0) return 0;
  const double ratio = std::log(kLevelTfSigmaMax / kLevelTfSigmaMin) / (kLevelTfRows - 2);
  return kLevelTfSigmaMin * std::exp(ratio * (row - 1));
}

int level_tf_row(double sigma) {
  if (!(sigma >= 0.5 * kLevelTfSigmaMin)) return 0;  // (NaN too)
  const double ratio = std::log(kLevelTfSigmaMax / kLevelTfSigmaMin) / (kLevelTfRows - 2);
  const double r = 1 + std::log(sigma / kLevelTfSigmaMin) / ratio;
  return std::clamp(int(std::lround(r)), 1, kLevelTfRows - 1);
}

std::vector<double> entry_prior(const TransferFunction& tf, std::span<const std::uint64_t> counts,
                                ValueRange over) {
  std::vector<double> prior;
  const int bins = int(counts.size());
  if (bins == 0 || !(over.lo < over.hi)) return prior;
  prior.resize(std::size_t(tf.size()), 0.0);
  for (int j = 0; j < tf.size(); ++j) {
    const double u = (tf.entry_value(j) - over.lo) / (over.hi - over.lo);
    if (u >= 0 && u <= 1) prior[std::size_t(j)] = double(counts[std::size_t(std::min(bins - 1, int(u * bins)))]);
  }
  double mean = 0;
  for (double p : prior) mean += p / double(prior.size());
  for (double& p : prior) p += kLevelTfPriorFloor * mean;
  return prior;
}

std::vector<Rgba> blurred_entries(const TransferFunction& tf, double sigma,
                                  std::span<const double> prior) {
  const int k = tf.size();
  std::vector<Rgba> out(tf.entries().begin(), tf.entries().end());
  const double s = sigma * k;  // in entries
  if (!(s > 0) || k == 0) return out;
  const int reach = int(std::ceil(kKernelSigmas * s));
  std::vector<double> w(std::size_t(2 * reach + 1));
  double total = 0;
  for (int d = -reach; d <= reach; ++d) {
    w[std::size_t(d + reach)] = std::exp(-0.5 * (d / s) * (d / s));
    total += w[std::size_t(d + reach)];
  }
  const bool weighted = int(prior.size()) == k;
  for (int j = 0; j < k; ++j) {
    // The kernel's weights times the prior, normalised (the plain kernel where the prior
    // vanishes over all of it).
    double norm = total;
    bool use_prior = false;
    if (weighted) {
      double t = 0;
      for (int d = -reach; d <= reach; ++d)
        t += w[std::size_t(d + reach)] * prior[std::size_t(std::clamp(j + d, 0, k - 1))];
      if (t > 0) {
        norm = t;
        use_prior = true;
      }
    }
    double a = 0, r = 0, g = 0, b = 0;
    for (int d = -reach; d <= reach; ++d) {
      const int at = std::clamp(j + d, 0, k - 1);
      const Rgba& e = tf.entry(at);
      const double wd =
          w[std::size_t(d + reach)] * (use_prior ? prior[std::size_t(at)] : 1.0) / norm;
      a += wd * e.a;
      r += wd * e.a * e.r;
      g += wd * e.a * e.g;
      b += wd * e.a * e.b;
    }
    Rgba& o = out[std::size_t(j)];
    o.a = float(a);
    if (a > 0) {
      o.r = float(std::min(1.0, r / a));
      o.g = float(std::min(1.0, g / a));
      o.b = float(std::min(1.0, b / a));
    }
  }
  return out;
}

}  // namespace tsp

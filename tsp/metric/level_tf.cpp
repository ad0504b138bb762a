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

std::vector<Rgba> blurred_entries(const TransferFunction& tf, double sigma) {
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
  for (int j = 0; j < k; ++j) {
    double a = 0, r = 0, g = 0, b = 0;
    for (int d = -reach; d <= reach; ++d) {
      const Rgba& e = tf.entry(std::clamp(j + d, 0, k - 1));
      const double wd = w[std::size_t(d + reach)] / total;
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

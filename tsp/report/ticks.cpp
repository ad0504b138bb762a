#include "tsp/report/ticks.h"

#include <algorithm>
#include <cmath>

#include "tsp/core/number_text.h"

namespace tsp {

std::vector<double> nice_ticks(double lo, double hi, int max_ticks) {
  max_ticks = std::max(2, max_ticks);
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo, hi};
  const double raw = (hi - lo) / double(max_ticks - 1);
  double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (int guard = 0; guard < 4; ++guard, mag *= 10)
    for (double m : {1.0, 2.0, 5.0}) {
      const double step = m * mag;
      const double first = std::ceil(lo / step - 1e-9), last = std::floor(hi / step + 1e-9);
      if (last - first + 1 > max_ticks) continue;
      std::vector<double> ticks;
      // k·m/10^j for a step below 1: 0.6, not 3 × 0.2 = 0.6000000000000001.
      const double inv = mag < 1 ? std::round(1 / mag) : 0;
      for (double k = first; k <= last; ++k) ticks.push_back(inv > 0 ? k * m / inv : k * step);
      if (ticks.size() >= 2) return ticks;
    }
  return {lo, hi};
}

std::string tick_text(double v, double step) {
  return number_text(std::fabs(v) < 1e-12 * std::fabs(step) ? 0.0 : v);
}

}  // namespace tsp

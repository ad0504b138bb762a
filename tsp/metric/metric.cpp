#include "tsp/metric/metric.h"

#include <algorithm>

#include "tsp/core/error.h"

namespace tsp {

namespace {
constexpr Metric kMetrics[] = {Metric::scalar, Metric::reference, Metric::approximate,
                               Metric::perceptual};
}  // namespace

const char* to_string(Metric m) {
  switch (m) {
    case Metric::scalar:
      return "scalar";
    case Metric::reference:
      return "reference";
    case Metric::approximate:
      return "approximate";
    case Metric::perceptual:
      return "perceptual";
  }
  return "?";
}

Metric parse_metric(const std::string& name) {
  for (Metric m : kMetrics)
    if (name == to_string(m)) return m;
  throw UsageError("unknown metric \"" + name +
                   "\" (expected scalar, reference, approximate or perceptual)");
}

std::int64_t MetricResult::transparent_count() const {
  return std::count(transparent.begin(), transparent.end(), std::uint8_t(1));
}

EntryRange entry_range(const TransferFunction& tf, const NodeStats& stats) {
  if (stats.empty()) return {0, -1};  // no voxel inside a stencil: nothing to draw
  return {tf.entry_of(stats.min), tf.entry_of(stats.max)};
}

}  // namespace tsp

#include "tsp/metric/metrics.h"

#include <algorithm>
#include <atomic>
#include <thread>

#include "tsp/metric/approximate_metric.h"
#include "tsp/core/error.h"
#include "tsp/metric/reference_metric.h"

namespace tsp {

namespace {
constexpr Metric kMetrics[] = {Metric::scalar, Metric::reference, Metric::approximate,
                               Metric::perceptual};
// Nodes handed to a worker at a time: large enough to amortise the atomic, small enough to
// balance nodes of very different entry ranges.
constexpr int kNodeChunk = 256;
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
  return {tf.entry_of(stats.min), tf.entry_of(stats.max)};
}

int resolve_threads(int threads) {
  if (threads > 0) return threads;
  return std::max(1, int(std::thread::hardware_concurrency()));
}

MetricResult compute_errors(Metric metric, const TspTree& tree, const TransferFunction& tf,
                            const BrickStore* bricks, int threads) {
  MetricResult out;
  if (metric == Metric::reference) {
    if (!bricks) throw UsageError("the reference metric needs the brick data, not only the tree");
    ReferenceMetric ref(*bricks);
    ref.update(tf, threads);
    ref.fill(out);
    return out;
  }
  const int n = tree.size();
  out.metric = metric;
  out.errors.spatial.resize(n);
  out.errors.temporal.resize(n);
  out.mean_colour.resize(n);
  out.transparent.resize(n);
  const ApproximateMetric am(metric, tf);
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int first; (first = next.fetch_add(kNodeChunk)) < n;) {
      const int last = std::min(n, first + kNodeChunk);
      for (int id = first; id < last; ++id) {
        const NodeResult r = am.evaluate(tree.stats(id));
        out.errors.spatial[id] = r.spatial;
        out.errors.temporal[id] = r.temporal;
        out.mean_colour[id] = r.mean;
        out.transparent[id] = r.transparent;
      }
    }
  };
  const int workers =
      std::max(1, std::min(resolve_threads(threads), (n + kNodeChunk - 1) / kNodeChunk));
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  return out;
}

}  // namespace tsp

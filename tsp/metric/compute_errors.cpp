#include "tsp/metric/compute_errors.h"

#include "tsp/core/error.h"
#include "tsp/core/parallel_for.h"
#include "tsp/metric/approximate_metric.h"
#include "tsp/metric/reference_metric.h"

namespace tsp {

namespace {
// Nodes handed to a worker at a time: large enough to amortise the scheduling, small enough to
// balance nodes of very different entry ranges.
constexpr int kNodeChunk = 256;
}  // namespace

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
  parallel_for(n, kNodeChunk, threads, [&](int, std::int64_t first, std::int64_t last) {
    for (auto id = first; id < last; ++id) {
      const NodeResult r = am.evaluate(tree.stats(int(id)));
      out.errors.spatial[id] = r.spatial;
      out.errors.temporal[id] = r.temporal;
      out.mean_colour[id] = r.mean;
      out.transparent[id] = r.transparent;
    }
  });
  return out;
}

}  // namespace tsp

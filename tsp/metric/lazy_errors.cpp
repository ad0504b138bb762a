#include "tsp/metric/lazy_errors.h"

#include <algorithm>
#include <atomic>
#include <cassert>

#include "tsp/core/error.h"
#include "tsp/core/parallel_for.h"

namespace tsp {

LazyErrors::LazyErrors(const TspTree& tree, Metric metric, const TransferFunction& tf)
    : tree_(tree), metric_(metric), tf_(&tf) {
  if (metric == Metric::reference)
    throw UsageError("the reference metric cannot be evaluated lazily from statistics alone");
  results_.resize(tree.size());
  stamp_.assign(tree.size(), kNever);
  errors_.spatial.assign(tree.size(), 0.0f);
  errors_.temporal.assign(tree.size(), 0.0f);
}

void LazyErrors::set_transfer_function(const TransferFunction& tf) {
  tf_ = &tf;
  tables_.reset();
  std::fill(stamp_.begin(), stamp_.end(), kNever);
}

void LazyErrors::sync() {
  // Rebuilding the O(K) tables (and the L*u*v* conversion) happens once per TF version.
  if (!tables_ || tables_->tf_version() != tf_->version())
    tables_ = std::make_unique<ApproximateMetric>(metric_, *tf_);
}

bool LazyErrors::refresh(int id) {
  const std::uint64_t now = tf_->version();
  std::uint64_t& stamp = stamp_[id];
  bool evaluated = false;
  if (stamp != now) {
    const EntryRange r = tables_->entry_range(tree_.stats(id));
    if (stamp == kNever || tf_->touched_since(stamp, r.lo, r.hi)) {
      results_[id] = tables_->evaluate(tree_.stats(id));
      evaluated = true;
    }
    stamp = now;
  }
  NodeResult& res = results_[id];
  // The approximate e_t = e_st · V depends on the whole TF (eq. 20): one multiplication, so it
  // is refreshed on every request instead of invalidating every node on every edit.
  if (metric_ == Metric::approximate && !res.transparent)
    res.temporal = float(tree_.stats(id).temporal_error * tables_->variation());
  errors_.spatial[id] = res.spatial;
  errors_.temporal[id] = res.temporal;
  return evaluated;
}

const NodeResult& LazyErrors::node(int id) {
  sync();
  evaluations_ += refresh(id);
  return results_[id];
}

NodeClassInfo LazyErrors::class_info(int id) const {
  assert(stamp_[std::size_t(id)] == tf_->version() && "node not made current for this TF");
  const NodeResult& r = results_[std::size_t(id)];
  return {r.spatial, r.transparent};
}

Rgba LazyErrors::mean_colour(int id) const {
  assert(stamp_[std::size_t(id)] == tf_->version() && "node not made current for this TF");
  return results_[std::size_t(id)].mean;
}

const NodeErrors& LazyErrors::errors_for_step(int t) {
  const TimeTree& time = tree_.time();
  assert(t >= 0 && t < time.steps());
  sync();
  for (int o = 0; o < tree_.octree().size(); ++o) {
    for (int tau = 0;; tau = time.child_holding(tau, t)) {
      evaluations_ += refresh(tree_.id(o, tau));
      if (time.is_leaf(tau)) break;
    }
  }
  return errors_;
}

const NodeErrors& LazyErrors::all(int threads) {
  sync();
  const int n = tree_.size();
  constexpr int kChunk = 1024;
  std::atomic<std::int64_t> evaluated{0};
  // Workers refresh disjoint nodes; refresh() touches only node id's slots.
  parallel_for(n, kChunk, threads, [&](int, std::int64_t first, std::int64_t last) {
    std::int64_t mine = 0;
    for (auto id = first; id < last; ++id) mine += refresh(int(id));
    evaluated += mine;
  });
  evaluations_ += evaluated;
  return errors_;
}

}  // namespace tsp

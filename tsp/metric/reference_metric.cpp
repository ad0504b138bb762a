#include "tsp/metric/reference_metric.h"

#include <algorithm>
#include <cmath>

#include "tsp/core/parallel_for.h"

namespace tsp {

namespace {

// Indices of the per-sample quantities summed for one pass (spec §4: expand d(c, ĉ)).
enum : int { kR, kG, kB, kA, kAA, kAR, kAG, kAB, kARGB2, kQuantities };
static_assert(kQuantities == 9);

// Below this the expanded variance analogue is rounding noise, not colour variation: the
// summed terms are at most ~4 per sample, so double cancellation leaves ~1e-15; a real σ̂ under
// 1e-6 is far below anything a transfer function can show.
constexpr double kRoundoffVariance = 1e-12;

struct ColourMoments {
  double sigma = 0, f = 0;
};

// σ̂ = sqrt((1/n) Σ d(c, ĉ)) and f̂ = sqrt(d(ĉ, 0)) from the sums of n samples.
inline ColourMoments moments(const double* s, double n) {
  const double inv = 1.0 / n;
  const double r = s[kR] * inv, g = s[kG] * inv, b = s[kB] * inv, a = s[kA] * inv;
  const double rgb2 = r * r + g * g + b * b;
  const double sum_d = s[kARGB2] - 2.0 * (r * s[kAR] + g * s[kAG] + b * s[kAB]) + rgb2 * s[kA] +
                       s[kAA] - 2.0 * a * s[kA] + n * a * a;
  const double var = sum_d * inv;
  return {var > kRoundoffVariance ? std::sqrt(var) : 0.0, std::sqrt(a * rgb2 + a * a)};
}

// Quantities of one TF entry, as summed per sample.
using EntryQuantities = std::array<double, kQuantities>;

}  // namespace

// Per-thread buffers: codes of one brick step, own-voxel indices, and two per-voxel sum
// buffers per time-tree level (the left and right child of the node being combined).
struct ReferenceMetric::BrickScratch {
  std::vector<std::uint16_t> codes;
  std::vector<int> own;
  std::vector<std::array<std::vector<double>, 2>> level;
  const std::vector<EntryQuantities>* quantities = nullptr;
};

ReferenceMetric::ReferenceMetric(const BrickStore& bricks)
    : bricks_(bricks), sums_(bricks.tree().size()), transparent_(bricks.tree().size(), 0) {}

void ReferenceMetric::compute_brick(int brick, const std::vector<std::uint16_t>& lut,
                                    BrickScratch& sc) {
  const TspTree& tree = bricks_.tree();
  const Octree& oct = tree.octree();
  const TimeTree& time = tree.time();
  const Box own = oct.brick_box(brick), samples = oct.brick_samples(brick);
  const int sx = samples.size(0), sy = samples.size(1);
  sc.codes.resize(std::size_t(samples.count()));
  // With a stencil, as in the builder's statistics: the voxels inside at some step only.
  std::vector<std::uint8_t> used;
  if (tree.has_stencil()) {
    std::vector<std::uint8_t> step(std::size_t(samples.count()));
    used.assign(step.size(), 0);
    for (int t = 0; t < time.steps(); ++t) {
      bricks_.read_inside(brick, t, step);
      for (std::size_t i = 0; i < step.size(); ++i) used[i] |= step[i];
    }
  }
  sc.own.clear();
  for (int z = own.lo[2]; z < own.hi[2]; ++z)
    for (int y = own.lo[1]; y < own.hi[1]; ++y)
      for (int x = own.lo[0]; x < own.hi[0]; ++x) {
        const int i = (x - samples.lo[0]) + sx * ((y - samples.lo[1]) + sy * (z - samples.lo[2]));
        if (used.empty() || used[std::size_t(i)]) sc.own.push_back(i);
      }
  const std::size_t n = sc.own.size();
  sc.level.resize(time.depth() + 1);
  for (auto& lv : sc.level)
    for (auto& buf : lv) buf.resize(n * kQuantities);
  const auto& q = *sc.quantities;
  const int octree_id = oct.brick_node(brick);

  // Post-order over the time tree: a node's per-voxel sums are its children's added, so only
  // two buffers per level are alive at once and every step is read exactly once.
  auto process = [&](auto&& self, int tau, int level, int slot) -> void {
    std::vector<double>& out = sc.level[level][slot];
    Sums total;
    total.voxels = double(n);
    if (time.is_leaf(tau)) {
      bricks_.read_brick(brick, time.span(tau).t0, sc.codes);
      double acc[kQuantities] = {};  // local: keeps the running sums out of memory
      for (std::size_t v = 0; v < n; ++v) {
        const EntryQuantities& e = q[lut[sc.codes[sc.own[v]]]];
        double* o = out.data() + v * kQuantities;
        for (int k = 0; k < kQuantities; ++k) {
          o[k] = e[k];
          acc[k] += e[k];
        }
      }
      for (int k = 0; k < kQuantities; ++k) total.s[k] = acc[k];
      total.samples = double(n);  // one step: ĉᵢ = cᵢ, so σ̂ᵢ = 0 and e_t's sum stays 0
    } else {
      self(self, time.left(tau), level + 1, 0);
      self(self, time.right(tau), level + 1, 1);
      const Sums& l = sums_[tree.id(octree_id, time.left(tau))];
      const Sums& r = sums_[tree.id(octree_id, time.right(tau))];
      total.samples = l.samples + r.samples;
      for (int k = 0; k < kQuantities; ++k) total.s[k] = l.s[k] + r.s[k];
      const double m = time.span(tau).length();
      const double* a = sc.level[level + 1][0].data();
      const double* b = sc.level[level + 1][1].data();
      const bool keep = level > 0;  // the root's per-voxel sums feed no parent
      double temporal = 0;
      for (std::size_t v = 0; v < n; ++v) {
        const std::size_t base = v * kQuantities;
        double sum[kQuantities];
        for (int k = 0; k < kQuantities; ++k) sum[k] = a[base + k] + b[base + k];
        if (keep) std::copy(sum, sum + kQuantities, out.data() + base);
        const ColourMoments cm = moments(sum, m);
        if (cm.f > 0) temporal += cm.sigma / cm.f;  // our rule: f̂ᵢ = 0 contributes 0
      }
      total.temporal = temporal;
    }
    sums_[tree.id(octree_id, tau)] = total;
  };
  process(process, 0, 0, 0);
}

void ReferenceMetric::combine_internal_nodes() {
  const TspTree& tree = bricks_.tree();
  const Octree& oct = tree.octree();
  const int tn = tree.time().size();
  // Children have larger breadth-first ids than their parent: walk ids downwards.
  for (int o = oct.size() - 1; o >= 0; --o) {
    // A stopped node (adaptive octrees) sums the leaves below it, read from its own brick.
    if (oct.node(o).is_leaf() && !oct.stopped(o)) continue;
    for (int tau = 0; tau < tn; ++tau) {
      Sums total;
      for (int c : oct.split_children(o)) {
        if (c < 0) continue;
        const Sums& s = sums_[tree.id(c, tau)];
        total.samples += s.samples;
        total.voxels += s.voxels;
        total.temporal += s.temporal;
        for (int k = 0; k < kQuantities; ++k) total.s[k] += s.s[k];
      }
      sums_[tree.id(o, tau)] = total;
    }
  }
}

int ReferenceMetric::update(const TransferFunction& tf, int threads) {
  const TspTree& tree = bricks_.tree();
  const Octree& oct = tree.octree();
  const Quantizer quant{tree.value_range()};
  // A voxel's decoded value lies within half a code of its original, so it can fall into an
  // entry beside [j_min, j_max] of the stored min/max: widen by a full code to catch it.
  const double code_width = tree.value_range().width() / kQuantMax;

  const ChangedEntries changed = last_ ? diff_entries(*last_, tf) : ChangedEntries::all(tf.size());
  std::vector<int> todo;
  for (int b = 0; b < oct.brick_count(); ++b) {
    const NodeStats& s = tree.stats(tree.id(oct.brick_node(b), 0));
    if (!last_ || changed.touches(tf.entry_of(s.min - code_width), tf.entry_of(s.max + code_width)))
      todo.push_back(b);
  }

  std::vector<std::uint16_t> lut(std::size_t(kQuantMax) + 1);
  for (int c = 0; c <= kQuantMax; ++c)
    lut[c] = std::uint16_t(tf.entry_of(quant.decode(std::uint16_t(c))));
  std::vector<EntryQuantities> quantities(tf.size());
  for (int j = 0; j < tf.size(); ++j) {
    const Rgba& c = tf.entry(j);
    const double r = c.r, g = c.g, b = c.b, a = c.a;
    quantities[j] = {r, g, b, a, a * a, a * r, a * g, a * b, a * (r * r + g * g + b * b)};
  }

  last_.reset();  // until this update completes, nothing counts as computed
  const auto count = std::int64_t(todo.size());
  std::vector<BrickScratch> scratch(std::size_t(parallel_workers(count, 1, threads)));
  for (BrickScratch& s : scratch) s.quantities = &quantities;
  parallel_for(count, 1, threads, [&](int worker, std::int64_t first, std::int64_t last) {
    for (auto i = first; i < last; ++i)
      compute_brick(todo[std::size_t(i)], lut, scratch[std::size_t(worker)]);
  });

  combine_internal_nodes();
  for (int id = 0; id < tree.size(); ++id) {
    const EntryRange r = entry_range(tf, tree.stats(id));
    transparent_[id] = tf.transparent(r.lo, r.hi);
  }
  last_ = tf;
  return int(todo.size());
}

NodeResult ReferenceMetric::node(int id) const {
  NodeResult out;
  if (transparent_[id]) {
    out.transparent = true;
    return out;
  }
  const Sums& s = sums_[id];
  if (s.samples <= 0) return out;
  const ColourMoments cm = moments(s.s.data(), s.samples);
  out.spatial = cm.f > 0 ? float(cm.sigma / cm.f) : 0.0f;
  out.temporal = s.voxels > 0 ? float(s.temporal / s.voxels) : 0.0f;
  out.mean = {float(s.s[kR] / s.samples), float(s.s[kG] / s.samples), float(s.s[kB] / s.samples),
              float(s.s[kA] / s.samples)};
  return out;
}

void ReferenceMetric::fill(MetricResult& out) const {
  const int n = bricks_.tree().size();
  out.metric = Metric::reference;
  out.errors.spatial.resize(n);
  out.errors.temporal.resize(n);
  out.mean_colour.resize(n);
  out.transparent.resize(n);
  for (int id = 0; id < n; ++id) {
    const NodeResult r = node(id);
    out.errors.spatial[id] = r.spatial;
    out.errors.temporal[id] = r.temporal;
    out.mean_colour[id] = r.mean;
    out.transparent[id] = r.transparent;
  }
}

}  // namespace tsp

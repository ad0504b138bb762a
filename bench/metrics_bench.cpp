// Benchmark of the error metrics (spec §4): whole-tree recompute of the TF-dependent metrics vs
// the reference metric on the same tree in the same run, the approximate metric's cost per TSP
// node and core, the reference metric's incremental update, and the lazy recompute of one step
// after a TF edit. The tree is synthetic and procedural (no file I/O, nothing held in memory):
// bricks are generated on demand, statistics come from one streaming pass.
//
//   metrics_bench [--dims N] [--steps T] [--brick B] [--threads W]   (default 256³ × 32, B = 32)
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "tsp/core/parallel_for.h"
#include "tsp/core/stopwatch.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/lazy_errors.h"
#include "tsp/metric/reference_metric.h"
#include "tsp/metric/tf_io.h"
#include "tsp/store/brick_store.h"

namespace {

constexpr int kNoiseTable = 1 << 16;
constexpr float kValueLo = -1.5f, kValueHi = 3.5f;  // covers every generated value

// A smooth field that drifts over time plus hashed noise: bricks see different ranges and
// spreads, and voxels change over time, so every metric has work to do.
class ProceduralStore : public tsp::BrickStore {
 public:
  ProceduralStore(tsp::Dims d, int steps, int brick) : tree_(d, steps, brick), noise_(kNoiseTable) {
    tree_.set_value_range({kValueLo, kValueHi});
    std::uint32_t s = 12345;
    for (float& n : noise_) {
      s = s * 1664525u + 1013904223u;
      n = 0.15f * (float(s >> 8) / float(1 << 24) - 0.5f);
    }
    for (int a = 0; a < 3; ++a) {
      wave_[a].resize(d[a]);
      for (int i = 0; i < d[a]; ++i) wave_[a][i] = float(std::sin(6.0 * i / d[a] + a));
    }
  }
  const tsp::TspTree& tree() const override { return tree_; }
  float value(int t, int x, int y, int z) const {
    const float drift = 0.02f * float(t);
    const std::uint32_t h = std::uint32_t(x) * 73856093u ^ std::uint32_t(y) * 19349663u ^
                            std::uint32_t(z) * 83492791u ^ std::uint32_t(t) * 2654435761u;
    return 1.0f + wave_[0][x] * wave_[1][y] + 0.5f * wave_[2][z] * (1.0f + drift) +
           noise_[h & (kNoiseTable - 1)];
  }
  void read_brick(int brick, int step, std::span<std::uint16_t> out) const override {
    const tsp::Box b = tree_.octree().brick_samples(brick);
    const tsp::Quantizer q{tree_.value_range()};
    std::size_t i = 0;
    for (int z = b.lo[2]; z < b.hi[2]; ++z)
      for (int y = b.lo[1]; y < b.hi[1]; ++y)
        for (int x = b.lo[0]; x < b.hi[0]; ++x) out[i++] = q.encode(value(step, x, y, z));
  }
  tsp::TspTree& mutable_tree() { return tree_; }

 private:
  tsp::TspTree tree_;
  std::vector<float> noise_;
  std::array<std::vector<float>, 3> wave_;
};

// Per-node running sums for the statistics pass.
struct StatSums {
  double n = 0, sum = 0, sum2 = 0, cov = 0, voxels = 0;
  float lo = INFINITY, hi = -INFINITY;
};

// Streams every brick once (post-order over the time tree, per-voxel Σv and Σv² per level) and
// fills every node's statistics (spec §2), leaves first, then internal octree nodes.
void compute_stats(ProceduralStore& store, int threads) {
  tsp::TspTree& tree = store.mutable_tree();
  const tsp::Octree& oct = tree.octree();
  const tsp::TimeTree& time = tree.time();
  const double width = tree.value_range().width();
  std::vector<StatSums> sums(tree.size());
  // Per-worker level buffers.
  using Levels = std::vector<std::array<std::vector<double>, 2>>;
  std::vector<Levels> levels(std::size_t(tsp::parallel_workers(oct.brick_count(), 1, threads)),
                             Levels(std::size_t(time.depth() + 1)));
  tsp::parallel_for(oct.brick_count(), 1, threads, [&](int w, std::int64_t first, std::int64_t last) {
    Levels& lv = levels[std::size_t(w)];
    for (int b = int(first); b < int(last); ++b) {
      const tsp::Box box = oct.brick_box(b);
      const std::size_t n = std::size_t(box.count());
      for (auto& l : lv)
        for (auto& v : l) v.assign(2 * n, 0.0);
      const int o = oct.brick_node(b);
      auto process = [&](auto&& self, int tau, int level, int slot) -> void {
        std::vector<double>& out = lv[level][slot];
        StatSums s;
        s.voxels = double(n);
        if (time.is_leaf(tau)) {
          const int t = time.span(tau).t0;
          std::size_t i = 0;
          for (int z = box.lo[2]; z < box.hi[2]; ++z)
            for (int y = box.lo[1]; y < box.hi[1]; ++y)
              for (int x = box.lo[0]; x < box.hi[0]; ++x, ++i) {
                const double v = store.value(t, x, y, z);
                out[2 * i] = v;
                out[2 * i + 1] = v * v;
                s.sum += v;
                s.sum2 += v * v;
                s.lo = std::min(s.lo, float(v));
                s.hi = std::max(s.hi, float(v));
              }
          s.n = double(n);
        } else {
          self(self, time.left(tau), level + 1, 0);
          self(self, time.right(tau), level + 1, 1);
          const StatSums& l = sums[tree.id(o, time.left(tau))];
          const StatSums& r = sums[tree.id(o, time.right(tau))];
          s.n = l.n + r.n, s.sum = l.sum + r.sum, s.sum2 = l.sum2 + r.sum2;
          s.lo = std::min(l.lo, r.lo), s.hi = std::max(l.hi, r.hi);
          const double m = time.span(tau).length();
          const auto& a = lv[level + 1][0];
          const auto& c = lv[level + 1][1];
          for (std::size_t i = 0; i < 2 * n; i += 2) {
            out[i] = a[i] + c[i];
            out[i + 1] = a[i + 1] + c[i + 1];
            const double mean = out[i] / m;
            const double var = std::max(0.0, out[i + 1] / m - mean * mean);
            s.cov += tsp::coefficient_of_variation(std::sqrt(var), mean, width);
          }
        }
        sums[tree.id(o, tau)] = s;
      };
      process(process, 0, 0, 0);
    }
  });
  for (int o = oct.size() - 1; o >= 0; --o) {
    if (oct.node(o).is_leaf()) continue;
    for (int tau = 0; tau < time.size(); ++tau) {
      StatSums s;
      for (int c : oct.node(o).children) {
        if (c < 0) continue;
        const StatSums& k = sums[tree.id(c, tau)];
        s.n += k.n, s.sum += k.sum, s.sum2 += k.sum2, s.cov += k.cov, s.voxels += k.voxels;
        s.lo = std::min(s.lo, k.lo), s.hi = std::max(s.hi, k.hi);
      }
      sums[tree.id(o, tau)] = s;
    }
  }
  for (int id = 0; id < tree.size(); ++id) {
    const StatSums& s = sums[id];
    tsp::NodeStats& st = tree.stats(id);
    st.mean = s.sum / s.n;
    st.std = std::sqrt(std::max(0.0, s.sum2 / s.n - st.mean * st.mean));
    st.min = s.lo;
    st.max = s.hi;
    st.spatial_error = float(tsp::coefficient_of_variation(st.std, st.mean, width));
    st.temporal_error = float(s.cov / s.voxels);
  }
}

int arg_int(int argc, char** argv, const char* name, int fallback) {
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], name) == 0) return std::atoi(argv[i + 1]);
  return fallback;
}

// A TF edit as a user makes it: recolour and reshape a band of entries.
void edit(tsp::TransferFunction& tf, int round) {
  const int k = tf.size(), first = (37 * round) % (k - 16);
  std::vector<tsp::Rgba> band(16);
  for (int j = 0; j < 16; ++j)
    band[j] = {float(j) / 16, 0.3f, float(round % 5) / 5, 0.05f * (j % 8)};
  tf.set_entries(first, band);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int n = arg_int(argc, argv, "--dims", 256);
  const int steps = arg_int(argc, argv, "--steps", 32);
  const int brick = arg_int(argc, argv, "--brick", tsp::kDefaultBrickSize);
  const int threads = tsp::resolve_threads(arg_int(argc, argv, "--threads", 0));
  ProceduralStore store({n, n, n}, steps, brick);
  const tsp::TspTree& tree = store.tree();
  std::printf(
      "tree          %d^3 x %d steps, brick %d: %d leaf bricks, %d octree nodes, %d TSP nodes\n", n,
      steps, brick, tree.octree().brick_count(), tree.octree().size(), tree.size());
  std::printf("threads       %d\n", threads);
  tsp::Stopwatch t0;
  compute_stats(store, threads);
  std::printf("statistics    %.0f ms (streaming pass, setup only)\n", t0.ms());

  tsp::TransferFunction tf = tsp::preset_transfer_function("filled", tree.value_range());
  std::printf("\nwhole-tree recompute, TF preset \"filled\", %d entries\n", tf.size());
  t0.restart();
  tsp::ReferenceMetric ref(store);
  ref.update(tf, threads);
  const double ref_ms = t0.ms();
  std::printf("  %-12s %12.1f ms\n", "reference", ref_ms);
  for (tsp::Metric m : {tsp::Metric::scalar, tsp::Metric::approximate, tsp::Metric::perceptual}) {
    std::vector<double> times;
    for (int rep = 0; rep < 5; ++rep) {
      t0.restart();
      const tsp::MetricResult r = tsp::compute_errors(m, tree, tf, nullptr, threads);
      times.push_back(t0.ms());
    }
    const double t = median(times);
    std::printf("  %-12s %12.3f ms   reference / this = %.0fx\n", tsp::to_string(m), t, ref_ms / t);
  }

  std::printf("\nper TSP node, one thread (median of 5)\n");
  for (tsp::Metric m : {tsp::Metric::approximate, tsp::Metric::perceptual}) {
    std::vector<double> times;
    for (int rep = 0; rep < 5; ++rep) {
      t0.restart();
      tsp::compute_errors(m, tree, tf, nullptr, 1);
      times.push_back(t0.ms());
    }
    double span = 0;
    for (int id = 0; id < tree.size(); ++id) {
      const tsp::EntryRange r = tsp::entry_range(tf, tree.stats(id));
      span += r.hi - r.lo + 1;
    }
    std::printf("  %-12s %8.3f us/node/core   (mean j_max - j_min + 1 = %.1f entries)\n",
                tsp::to_string(m), 1000.0 * median(times) / tree.size(), span / tree.size());
  }

  std::printf("\nreference metric after a 16-entry edit (skips bricks not touching it)\n");
  for (int round = 1; round <= 3; ++round) {
    edit(tf, round);
    t0.restart();
    const int reread = ref.update(tf, threads);
    std::printf("  edit %d: %4d of %d bricks re-read, %10.1f ms\n", round, reread,
                tree.octree().brick_count(), t0.ms());
  }

  std::printf("\nlazy recompute of one step after a TF edit (median of 20 edits)\n");
  for (tsp::Metric m : {tsp::Metric::approximate, tsp::Metric::perceptual}) {
    tsp::TransferFunction live = tsp::preset_transfer_function("filled", tree.value_range());
    tsp::LazyErrors lazy(tree, m, live);
    t0.restart();
    lazy.errors_for_step(steps / 2);
    const double cold = t0.ms();
    std::vector<double> times;
    std::int64_t evaluated = 0;
    for (int round = 0; round < 20; ++round) {
      edit(live, round);
      const std::int64_t before = lazy.evaluations();
      t0.restart();
      lazy.errors_for_step((round * 7) % steps);
      times.push_back(t0.ms());
      evaluated += lazy.evaluations() - before;
    }
    std::printf(
        "  %-12s first step %.3f ms; after an edit %.3f ms (%.0f nodes evaluated per step)\n",
        tsp::to_string(m), cold, median(times), double(evaluated) / 20);
  }
  return 0;
}

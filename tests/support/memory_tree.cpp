#include "support/memory_tree.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "tsp/core/error.h"

namespace tsptest {

using tsp::Box;
using tsp::TspTree;
using tsp::ValueRange;

MemorySeries MemorySeries::generate(tsp::Dims dims, int steps,
                                    const std::function<float(int, int, int, int)>& f) {
  MemorySeries s{dims, steps, {}};
  s.values.reserve(std::size_t(steps) * dims.count());
  for (int t = 0; t < steps; ++t)
    for (int z = 0; z < dims.z; ++z)
      for (int y = 0; y < dims.y; ++y)
        for (int x = 0; x < dims.x; ++x) s.values.push_back(f(t, x, y, z));
  return s;
}

MemorySeries MemorySeries::uniform(tsp::Dims dims, int steps, unsigned seed, float lo, float hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(lo, hi);
  return generate(dims, steps, [&](int, int, int, int) { return u(rng); });
}

namespace {
ValueRange data_range(const MemorySeries& s) {
  auto [lo, hi] = std::minmax_element(s.values.begin(), s.values.end());
  return {*lo, *hi};
}
}  // namespace

TspTree brute_force_tree(const MemorySeries& s, int brick_size, std::optional<ValueRange> range) {
  TspTree tree(s.dims, s.steps, brick_size);
  const ValueRange r = range ? *range : data_range(s);
  tree.set_value_range(r);
  const auto& oct = tree.octree();
  const auto& time = tree.time();
  for (int o = 0; o < oct.size(); ++o) {
    const Box b = oct.node(o).box;
    for (int tau = 0; tau < time.size(); ++tau) {
      const tsp::Span sp = time.span(tau);
      const double m = sp.length();
      double sum = 0, n_all = 0, cov_sum = 0, voxels = 0;
      float lo = INFINITY, hi = -INFINITY;
      for (int z = b.lo[2]; z < b.hi[2]; ++z)
        for (int y = b.lo[1]; y < b.hi[1]; ++y)
          for (int x = b.lo[0]; x < b.hi[0]; ++x) {
            double vsum = 0;
            for (int t = sp.t0; t <= sp.t1; ++t) {
              const float v = s.at(t, x, y, z);
              vsum += v;
              lo = std::min(lo, v);
              hi = std::max(hi, v);
            }
            const double vmean = vsum / m;
            double vdev = 0;
            for (int t = sp.t0; t <= sp.t1; ++t)
              vdev += (s.at(t, x, y, z) - vmean) * (s.at(t, x, y, z) - vmean);
            cov_sum += tsp::coefficient_of_variation(std::sqrt(vdev / m), vmean, r.width());
            sum += vsum;
            n_all += m;
            voxels += 1;
          }
      const double mean = sum / n_all;
      double dev = 0;
      for (int z = b.lo[2]; z < b.hi[2]; ++z)
        for (int y = b.lo[1]; y < b.hi[1]; ++y)
          for (int x = b.lo[0]; x < b.hi[0]; ++x)
            for (int t = sp.t0; t <= sp.t1; ++t)
              dev += (s.at(t, x, y, z) - mean) * (s.at(t, x, y, z) - mean);
      tsp::NodeStats& st = tree.stats(tree.id(o, tau));
      st.mean = mean;
      st.std = std::sqrt(dev / n_all);
      st.min = lo;
      st.max = hi;
      st.spatial_error = float(tsp::coefficient_of_variation(st.std, mean, r.width()));
      st.temporal_error = float(cov_sum / voxels);
    }
  }
  return tree;
}

MemoryBrickStore::MemoryBrickStore(const MemorySeries& series, int brick_size,
                                   std::optional<ValueRange> range)
    : series_(series), tree_(brute_force_tree(series, brick_size, range)) {}

void MemoryBrickStore::read_brick(int brick, int step, std::span<std::uint16_t> out) const {
  ++reads_;
  if (fail_)
    throw tsp::IoError("memory store: injected read failure of brick " + std::to_string(brick));
  const Box b = tree_.octree().brick_samples(brick);
  const tsp::Quantizer q{tree_.value_range()};
  std::size_t i = 0;
  for (int z = b.lo[2]; z < b.hi[2]; ++z)
    for (int y = b.lo[1]; y < b.hi[1]; ++y)
      for (int x = b.lo[0]; x < b.hi[0]; ++x) out[i++] = q.encode(series_.at(step, x, y, z));
}

float MemoryBrickStore::decoded(int t, int x, int y, int z) const {
  const tsp::Quantizer q{tree_.value_range()};
  return q.decode(q.encode(series_.at(t, x, y, z)));
}

}  // namespace tsptest

#include "tsp/build/brick_stats.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace tsp {
namespace {

// Voxels processed together: the per-time-node arrays of one chunk (2T × 256 × 16 bytes) stay
// in cache, and the inner loops run over contiguous voxels.
constexpr int kChunkVoxels = 256;

// The spec's COV rule, inlined for the per-voxel loop; must match coefficient_of_variation().
// Written without early returns so that the per-voxel loop can be vectorized.
inline double cov_rule(double sigma, double mean, double width) {
  const double den = mean != 0 ? std::fabs(mean) : width;
  const double r = sigma / (den != 0 ? den : 1.0);
  const bool zero = (sigma == 0) | (den == 0);  // no short circuit: no branch
  return zero ? 0.0 : r;
}

// Per-voxel temporal mean and M2 of one chunk for every time node: [node][voxel].
struct ChunkWork {
  std::vector<double> mean, m2;
  std::vector<double> cov;    // one time node's per-voxel COV terms
  std::vector<Moments> node;  // the chunk's moments per time node
  explicit ChunkWork(int node_count)
      : mean(std::size_t(node_count) * kChunkVoxels),
        m2(mean.size()),
        cov(kChunkVoxels),
        node(node_count) {}
};

// Σ v[0..n) in a fixed order with independent lanes: fast, and the same on every run.
double lane_sum(const double* v, int n) {
  constexpr int kLanes = 4;
  double acc[kLanes] = {0, 0, 0, 0};
  int i = 0;
  for (; i + kLanes <= n; i += kLanes)
    for (int j = 0; j < kLanes; ++j) acc[j] += v[i + j];
  for (; i < n; ++i) acc[0] += v[i];
  return (acc[0] + acc[1]) + (acc[2] + acc[3]);
}

void process_chunk(const TimeTree& time, std::span<const float> series, std::int64_t step_stride,
                   const std::vector<std::int64_t>& idx, int count, double width, ChunkWork& w,
                   std::span<NodeAccum> out) {
  const int K = kChunkVoxels;
  // Leaves, one step each: per-voxel values, and the chunk's moments by the two-pass formula.
  for (int t = 0; t < time.steps(); ++t) {
    const int leaf = time.leaf_of(t);
    double* mean = w.mean.data() + std::size_t(leaf) * K;
    double* m2 = w.m2.data() + std::size_t(leaf) * K;
    const float* step = series.data() + std::size_t(t) * step_stride;
    double sum = 0;
    float lo = step[idx[0]], hi = lo;
    for (int c = 0; c < count; ++c) {
      const float v = step[idx[c]];
      mean[c] = v;
      m2[c] = 0;
      sum += v;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    const double cm = sum / count;
    double dev = 0;
    for (int c = 0; c < count; ++c) dev += (mean[c] - cm) * (mean[c] - cm);
    w.node[leaf] = Moments{double(count), cm, dev, lo, hi};
  }
  // Internal time nodes bottom-up (breadth-first ids put children after their parent): per-voxel
  // temporal moments by Chan's formula, their COV sum for e_st, and the chunk's moments merged
  // from the two children (the same pairwise identity, exact for pooled groups).
  for (int id = time.size() - 1; id >= 0; --id) {
    if (time.is_leaf(id)) continue;
    const int l = time.left(id), r = time.right(id);
    const double nl = time.span(l).length(), nr = time.span(r).length(), m = nl + nr;
    const double wr = nr / m, k = nl * nr / m;
    double* mean = w.mean.data() + std::size_t(id) * K;
    double* m2 = w.m2.data() + std::size_t(id) * K;
    const double* ml = w.mean.data() + std::size_t(l) * K;
    const double* m2l = w.m2.data() + std::size_t(l) * K;
    const double* mr = w.mean.data() + std::size_t(r) * K;
    const double* m2r = w.m2.data() + std::size_t(r) * K;
    double* cov = w.cov.data();
    // Element-wise, so the vectorizer can run it (the sum over voxels follows separately).
    for (int c = 0; c < count; ++c) {
      const double d = mr[c] - ml[c];
      mean[c] = ml[c] + d * wr;
      m2[c] = m2l[c] + m2r[c] + d * d * k;
      cov[c] = cov_rule(std::sqrt(m2[c] / m), mean[c], width);
    }
    w.node[id] = w.node[l];
    w.node[id].merge(w.node[r]);
    out[id].cov_sum += lane_sum(cov, count);
  }
  for (int id = 0; id < time.size(); ++id) {
    out[id].moments.merge(w.node[id]);
    out[id].voxels += count;
  }
}

}  // namespace

void brick_time_stats(const TimeTree& time, const Box& samples, const Box& own,
                      std::span<const float> series, double range_width, std::span<NodeAccum> out) {
  assert(int(out.size()) == time.size());
  const std::int64_t stride = samples.count();
  assert(std::int64_t(series.size()) == stride * time.steps());
  for (int a = 0; a < 3; ++a) assert(own.lo[a] >= samples.lo[a] && own.hi[a] <= samples.hi[a]);
  for (NodeAccum& a : out) a = NodeAccum{};

  ChunkWork work(time.size());
  std::vector<std::int64_t> idx(kChunkVoxels);
  int count = 0;
  const int sx = samples.size(0), sy = samples.size(1);
  for (int z = own.lo[2]; z < own.hi[2]; ++z)
    for (int y = own.lo[1]; y < own.hi[1]; ++y) {
      const std::int64_t row =
          std::int64_t(sx) * ((y - samples.lo[1]) + std::int64_t(sy) * (z - samples.lo[2]));
      for (int x = own.lo[0]; x < own.hi[0]; ++x) {
        idx[count++] = row + (x - samples.lo[0]);
        if (count == kChunkVoxels) {
          process_chunk(time, series, stride, idx, count, range_width, work, out);
          count = 0;
        }
      }
    }
  if (count > 0) process_chunk(time, series, stride, idx, count, range_width, work, out);
}

}  // namespace tsp

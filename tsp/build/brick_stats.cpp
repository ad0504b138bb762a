#include "tsp/build/brick_stats.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <optional>
#include <vector>

namespace tsp {
namespace {

// Voxels processed together: the per-level arrays of one chunk stay in cache, and the inner
// loops run over contiguous voxels.
constexpr int kChunkVoxels = 256;
// Largest per-worker buffer of the flat pass (2 · time nodes · kChunkVoxels doubles): 4 MiB, a
// series of about 1000 steps.
constexpr std::size_t kFlatBufferBytes = std::size_t(4) << 20;

// The spec's COV rule, inlined for the per-voxel loop; must match coefficient_of_variation().
// Written without early returns so that the per-voxel loop can be vectorized.
inline double cov_rule(double sigma, double mean, double width) {
  const double den = mean != 0 ? std::fabs(mean) : width;
  const double r = sigma / (den != 0 ? den : 1.0);
  const bool zero = (sigma == 0) | (den == 0);  // no short circuit: no branch
  return zero ? 0.0 : r;
}

// Per-voxel temporal mean and M2 of one chunk, one pair of buffers per time-tree level and side:
// the time tree is walked depth first, so only the path being combined is held (O(depth · K)
// memory, not O(T · K)).
struct ChunkWork {
  std::vector<std::array<std::vector<double>, 2>> mean, m2;  // [level][side][voxel]
  std::vector<double> cov;                                   // one node's per-voxel COV terms
  explicit ChunkWork(int depth)
      : mean(std::size_t(depth) + 1), m2(std::size_t(depth) + 1), cov(kChunkVoxels) {
    for (auto* buffers : {&mean, &m2})
      for (auto& level : *buffers)
        for (auto& side : level) side.assign(kChunkVoxels, 0.0);
  }
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

struct ChunkPass {
  const TimeTree& time;
  std::span<const float> series;
  std::int64_t step_stride;
  const std::vector<std::int64_t>& idx;
  int count;
  double width;
  ChunkWork& w;
  std::span<NodeAccum> out;

  // Time node id into w's buffers of (level, side); returns the chunk's moments over its span
  // and adds them (and, for internal nodes, the per-voxel COV sum for e_st) to out[id].
  Moments visit(int id, int level, int side) {
    double* mean = w.mean[std::size_t(level)][std::size_t(side)].data();
    double* m2 = w.m2[std::size_t(level)][std::size_t(side)].data();
    Moments node;
    if (time.is_leaf(id)) {
      // One step: per-voxel values, and the chunk's moments by the two-pass formula.
      const float* step = series.data() + std::size_t(time.span(id).t0) * step_stride;
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
      node = Moments{double(count), cm, dev, lo, hi};
    } else {
      // Per-voxel temporal moments by Chan's formula from the two children, their COV sum for
      // e_st, and the chunk's moments merged from the children (the same pairwise identity).
      const int l = time.left(id), r = time.right(id);
      const Moments left = visit(l, level + 1, 0), right = visit(r, level + 1, 1);
      const double nl = time.span(l).length(), nr = time.span(r).length(), m = nl + nr;
      const double wr = nr / m, k = nl * nr / m;
      const double* ml = w.mean[std::size_t(level) + 1][0].data();
      const double* m2l = w.m2[std::size_t(level) + 1][0].data();
      const double* mr = w.mean[std::size_t(level) + 1][1].data();
      const double* m2r = w.m2[std::size_t(level) + 1][1].data();
      double* cov = w.cov.data();
      // Element-wise, so the vectorizer can run it (the sum over voxels follows separately).
      for (int c = 0; c < count; ++c) {
        const double d = mr[c] - ml[c];
        mean[c] = ml[c] + d * wr;
        m2[c] = m2l[c] + m2r[c] + d * d * k;
        cov[c] = cov_rule(std::sqrt(m2[c] / m), mean[c], width);
      }
      node = left;
      node.merge(right);
      out[std::size_t(id)].cov_sum += lane_sum(cov, count);
    }
    out[std::size_t(id)].moments.merge(node);
    out[std::size_t(id)].voxels += count;
    return node;
  }
};

// The same statistics with every time node's per-voxel buffers held at once, bottom-up in id
// order: faster (contiguous passes the vectorizer runs well) while those buffers stay small.
// Per-voxel temporal mean and M2 of one chunk for every time node: [node][voxel].
struct FlatWork {
  std::vector<double> mean, m2;
  std::vector<double> cov;    // one time node's per-voxel COV terms
  std::vector<Moments> node;  // the chunk's moments per time node
  explicit FlatWork(int node_count)
      : mean(std::size_t(node_count) * kChunkVoxels),
        m2(mean.size()),
        cov(kChunkVoxels),
        node(node_count) {}
};

void process_chunk_flat(const TimeTree& time, std::span<const float> series, std::int64_t step_stride,
                   const std::vector<std::int64_t>& idx, int count, double width, FlatWork& w,
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

void process_chunk(const TimeTree& time, std::span<const float> series, std::int64_t step_stride,
                   const std::vector<std::int64_t>& idx, int count, double width, ChunkWork& w,
                   std::span<NodeAccum> out) {
  ChunkPass{time, series, step_stride, idx, count, width, w, out}.visit(0, 0, 0);
}

}  // namespace

void brick_time_stats(const TimeTree& time, const Box& samples, const Box& own,
                      std::span<const float> series, double range_width, std::span<NodeAccum> out) {
  assert(int(out.size()) == time.size());
  const std::int64_t stride = samples.count();
  assert(std::int64_t(series.size()) == stride * time.steps());
  for (int a = 0; a < 3; ++a) assert(own.lo[a] >= samples.lo[a] && own.hi[a] <= samples.hi[a]);
  for (NodeAccum& a : out) a = NodeAccum{};

  // Below kFlatBufferBytes of per-node buffers the flat pass is faster; above it (long series)
  // the depth-first pass keeps memory at O(depth) per worker. Both give the same bits.
  const bool flat = std::size_t(time.size()) * kChunkVoxels * 2 * sizeof(double) <= kFlatBufferBytes;
  std::optional<FlatWork> flat_work;
  std::optional<ChunkWork> work;
  if (flat)
    flat_work.emplace(time.size());
  else
    work.emplace(time.depth());
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
          if (flat)
            process_chunk_flat(time, series, stride, idx, count, range_width, *flat_work, out);
          else
            process_chunk(time, series, stride, idx, count, range_width, *work, out);
          count = 0;
        }
      }
    }
  if (count > 0) {
    if (flat)
      process_chunk_flat(time, series, stride, idx, count, range_width, *flat_work, out);
    else
      process_chunk(time, series, stride, idx, count, range_width, *work, out);
  }
}

}  // namespace tsp

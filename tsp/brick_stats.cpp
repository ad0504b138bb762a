#include "tsp/brick_stats.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace tsp {
namespace {

// Voxels processed together: the per-time-node arrays of one chunk (about 2T × 256 × 24 bytes)
// stay in cache, and the inner loops run over contiguous voxels.
constexpr int kChunkVoxels = 256;

// The spec's COV rule, inlined for the per-voxel loop; must match coefficient_of_variation().
inline double cov_rule(double sigma, double mean, double width) {
  if (sigma == 0) return 0;
  if (mean != 0) return sigma / std::fabs(mean);
  return width > 0 ? sigma / width : 0;
}

// Per-voxel statistics of one chunk for every time node: [node][voxel].
struct ChunkWork {
  int nodes = 0;
  std::vector<double> mean, m2;
  std::vector<float> mn, mx;
  explicit ChunkWork(int node_count)
      : nodes(node_count),
        mean(std::size_t(node_count) * kChunkVoxels),
        m2(mean.size()),
        mn(mean.size()),
        mx(mean.size()) {}
};

void process_chunk(const TimeTree& time, std::span<const float> series, std::int64_t step_stride,
                   const std::vector<std::int64_t>& idx, int count, double width, ChunkWork& w,
                   std::span<NodeAccum> out) {
  const int K = kChunkVoxels;
  // Leaves: one step each.
  for (int t = 0; t < time.steps(); ++t) {
    const std::size_t base = std::size_t(time.leaf_of(t)) * K;
    const float* step = series.data() + std::size_t(t) * step_stride;
    for (int c = 0; c < count; ++c) {
      float v = step[idx[c]];
      w.mean[base + c] = v;
      w.m2[base + c] = 0;
      w.mn[base + c] = v;
      w.mx[base + c] = v;
    }
  }
  // Internal time nodes bottom-up: breadth-first ids put children after their parent.
  for (int id = time.size() - 1; id >= 0; --id) {
    if (time.is_leaf(id)) continue;
    const int l = time.left(id), r = time.right(id);
    const double nl = time.span(l).length(), nr = time.span(r).length();
    const double wr = nr / (nl + nr), k = nl * nr / (nl + nr);
    const std::size_t b = std::size_t(id) * K, bl = std::size_t(l) * K, br = std::size_t(r) * K;
    for (int c = 0; c < count; ++c) {
      double d = w.mean[br + c] - w.mean[bl + c];
      w.mean[b + c] = w.mean[bl + c] + d * wr;
      w.m2[b + c] = w.m2[bl + c] + w.m2[br + c] + d * d * k;
      w.mn[b + c] = std::min(w.mn[bl + c], w.mn[br + c]);
      w.mx[b + c] = std::max(w.mx[bl + c], w.mx[br + c]);
    }
  }
  // Fold the chunk into each time node's accumulator: exact two-pass moments within the chunk,
  // then one pairwise merge.
  for (int id = 0; id < time.size(); ++id) {
    const std::size_t b = std::size_t(id) * K;
    const double m = time.span(id).length();
    double sum = 0, m2 = 0, cov = 0;
    float lo = w.mn[b], hi = w.mx[b];
    for (int c = 0; c < count; ++c) sum += w.mean[b + c];
    const double cm = sum / count;
    double dev = 0;
    for (int c = 0; c < count; ++c) {
      double d = w.mean[b + c] - cm;
      dev += d * d;
      m2 += w.m2[b + c];
      lo = std::min(lo, w.mn[b + c]);
      hi = std::max(hi, w.mx[b + c]);
    }
    if (!time.is_leaf(id))
      for (int c = 0; c < count; ++c)
        cov += cov_rule(std::sqrt(w.m2[b + c] / m), w.mean[b + c], width);
    Moments chunk;
    chunk.n = double(count) * m;
    chunk.mean = cm;
    chunk.m2 = m2 + m * dev;
    chunk.min = lo;
    chunk.max = hi;
    out[id].moments.merge(chunk);
    out[id].cov_sum += cov;
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

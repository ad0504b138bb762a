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

// One chunk at one time step: the voxels' values into mean (m2 = 0), and the chunk's moments by
// the two-pass formula.
inline Moments leaf_moments(const float* step, const std::vector<std::int64_t>& idx, int count,
                            double* __restrict mean, double* __restrict m2) {
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
  return Moments{double(count), cm, dev, lo, hi};
}

// (The buffers never overlap: __restrict lets the loops vectorize without alias checks.)
// An internal time node from its children's per-voxel moments (spans of nl and nr steps): its
// per-voxel mean and M2 by Chan's formula, and the sum of its voxels' COV terms for e_st.
// Element-wise, so the vectorizer can run it (the sum over voxels follows separately).
inline double combine_voxels(const double* __restrict ml, const double* __restrict m2l,
                             const double* __restrict mr, const double* __restrict m2r, double nl,
                             double nr, int count, double width, double* __restrict mean,
                             double* __restrict m2, double* __restrict cov) {
  const double m = nl + nr, wr = nr / m, k = nl * nr / m;
  for (int c = 0; c < count; ++c) {
    const double d = mr[c] - ml[c];
    mean[c] = ml[c] + d * wr;
    m2[c] = m2l[c] + m2r[c] + d * d * k;
    cov[c] = cov_rule(std::sqrt(m2[c] / m), mean[c], width);
  }
  return lane_sum(cov, count);
}

// What both passes read: the brick's series, the chunk's voxels, the output accumulators.
struct Chunk {
  const TimeTree& time;
  std::span<const float> series;
  std::int64_t step_stride;
  const std::vector<std::int64_t>& idx;
  int count;
  double width;
  std::span<NodeAccum> out;

  const float* step(int t) const { return series.data() + std::size_t(t) * step_stride; }
  double length(int id) const { return time.span(id).length(); }
};

// Flat pass: every time node's per-voxel buffers held at once ([node][voxel]), leaves first, then
// internal nodes bottom-up in id order (breadth-first ids put children after their parent).
// Faster (contiguous passes), while the buffers stay small.
struct FlatPass {
  std::vector<double> mean, m2, cov;
  std::vector<Moments> node;  // the chunk's moments per time node
  explicit FlatPass(int node_count)
      : mean(std::size_t(node_count) * kChunkVoxels),
        m2(mean.size()),
        cov(kChunkVoxels),
        node(std::size_t(node_count)) {}

  void run(const Chunk& ch) {
    auto at = [](std::vector<double>& v, int id) {
      return v.data() + std::size_t(id) * kChunkVoxels;
    };
    for (int t = 0; t < ch.time.steps(); ++t) {
      const int leaf = ch.time.leaf_of(t);
      node[std::size_t(leaf)] =
          leaf_moments(ch.step(t), ch.idx, ch.count, at(mean, leaf), at(m2, leaf));
    }
    for (int id = ch.time.size() - 1; id >= 0; --id) {
      if (ch.time.is_leaf(id)) continue;
      const int l = ch.time.left(id), r = ch.time.right(id);
      ch.out[std::size_t(id)].cov_sum +=
          combine_voxels(at(mean, l), at(m2, l), at(mean, r), at(m2, r), ch.length(l), ch.length(r),
                         ch.count, ch.width, at(mean, id), at(m2, id), cov.data());
      node[std::size_t(id)] = node[std::size_t(l)];
      node[std::size_t(id)].merge(node[std::size_t(r)]);
    }
    for (int id = 0; id < ch.time.size(); ++id) {
      ch.out[std::size_t(id)].moments.merge(node[std::size_t(id)]);
      ch.out[std::size_t(id)].voxels += ch.count;
    }
  }
};

// Depth-first pass: one pair of buffers per time-tree level and side, so only the path being
// combined is held (O(depth · K) memory, not O(T · K)), for long series.
struct DepthFirstPass {
  std::vector<std::array<std::vector<double>, 2>> mean, m2;  // [level][side][voxel]
  std::vector<double> cov;
  explicit DepthFirstPass(int depth)
      : mean(std::size_t(depth) + 1), m2(std::size_t(depth) + 1), cov(kChunkVoxels) {
    for (auto* buffers : {&mean, &m2})
      for (auto& level : *buffers)
        for (auto& side : level) side.assign(kChunkVoxels, 0.0);
  }

  void run(const Chunk& ch) { visit(ch, 0, 0, 0); }

  // Time node id into the buffers of (level, side); returns the chunk's moments over its span
  // and adds them (and, for internal nodes, the COV sum for e_st) to out[id].
  Moments visit(const Chunk& ch, int id, int level, int side) {
    const auto lv = std::size_t(level), sd = std::size_t(side);
    Moments node;
    if (ch.time.is_leaf(id)) {
      node = leaf_moments(ch.step(ch.time.span(id).t0), ch.idx, ch.count, mean[lv][sd].data(),
                          m2[lv][sd].data());
    } else {
      const int l = ch.time.left(id), r = ch.time.right(id);
      node = visit(ch, l, level + 1, 0);
      node.merge(visit(ch, r, level + 1, 1));
      ch.out[std::size_t(id)].cov_sum +=
          combine_voxels(mean[lv + 1][0].data(), m2[lv + 1][0].data(), mean[lv + 1][1].data(),
                         m2[lv + 1][1].data(), ch.length(l), ch.length(r), ch.count, ch.width,
                         mean[lv][sd].data(), m2[lv][sd].data(), cov.data());
    }
    ch.out[std::size_t(id)].moments.merge(node);
    ch.out[std::size_t(id)].voxels += ch.count;
    return node;
  }
};

}  // namespace

void brick_time_stats(const TimeTree& time, const Box& samples, const Box& own,
                      std::span<const float> series, double range_width, std::span<NodeAccum> out,
                      std::span<const std::uint8_t> use) {
  assert(int(out.size()) == time.size());
  const std::int64_t stride = samples.count();
  assert(std::int64_t(series.size()) == stride * time.steps());
  for (int a = 0; a < 3; ++a) assert(own.lo[a] >= samples.lo[a] && own.hi[a] <= samples.hi[a]);
  for (NodeAccum& a : out) a = NodeAccum{};

  // Below kFlatBufferBytes of per-node buffers the flat pass is faster; above it (long series)
  // the depth-first pass keeps memory at O(depth) per worker. Both give the same bits.
  const bool flat =
      std::size_t(time.size()) * kChunkVoxels * 2 * sizeof(double) <= kFlatBufferBytes;
  std::optional<FlatPass> flat_pass;
  std::optional<DepthFirstPass> deep_pass;
  if (flat)
    flat_pass.emplace(time.size());
  else
    deep_pass.emplace(time.depth());
  std::vector<std::int64_t> idx(kChunkVoxels);
  int count = 0;
  auto run_chunk = [&] {
    const Chunk ch{time, series, stride, idx, count, range_width, out};
    if (flat)
      flat_pass->run(ch);
    else
      deep_pass->run(ch);
  };
  const int sx = samples.size(0), sy = samples.size(1);
  for (int z = own.lo[2]; z < own.hi[2]; ++z)
    for (int y = own.lo[1]; y < own.hi[1]; ++y) {
      const std::int64_t row =
          std::int64_t(sx) * ((y - samples.lo[1]) + std::int64_t(sy) * (z - samples.lo[2]));
      for (int x = own.lo[0]; x < own.hi[0]; ++x) {
        const std::int64_t i = row + (x - samples.lo[0]);
        if (!use.empty() && !use[std::size_t(i)]) continue;
        idx[count++] = i;
        if (count == kChunkVoxels) {
          run_chunk();
          count = 0;
        }
      }
    }
  if (count > 0) run_chunk();
}

}  // namespace tsp

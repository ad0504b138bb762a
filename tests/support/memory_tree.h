// Test-only trees: statistics computed by brute force from an in-memory time series (spec §2,
// two passes in double), and an in-memory BrickStore of the quantized bricks.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "tsp/store/brick_store.h"
#include "tsp/tree/tsp_tree.h"

namespace tsptest {

/// A scalar time series in memory: value(t, x, y, z) = values[t·count + x + X·(y + Y·z)].
struct MemorySeries {
  tsp::Dims dims;
  int steps = 1;
  std::vector<float> values;
  /// A series filled by f(t, x, y, z).
  static MemorySeries generate(tsp::Dims dims, int steps,
                               const std::function<float(int, int, int, int)>& f);
  /// Samples drawn uniformly from [lo, hi) in generate's order by a std::mt19937 seeded so.
  static MemorySeries uniform(tsp::Dims dims, int steps, unsigned seed, float lo, float hi);
  /// Sample at step t, voxel (x, y, z).
  float at(int t, int x, int y, int z) const {
    return values[std::size_t(t) * dims.count() + x +
                  std::size_t(dims.x) * (y + std::size_t(dims.y) * z)];
  }
};

/// Brute-force statistics of every TSP node of a tree over series (range: the COV fallback and
/// quantization range; default the series' min/max).
tsp::TspTree brute_force_tree(const MemorySeries& series, int brick_size,
                              std::optional<tsp::ValueRange> range = {});

/// The series quantized into bricks, with the brute-force tree.
class MemoryBrickStore : public tsp::BrickStore {
 public:
  /// Quantizes series over the tree's value range.
  MemoryBrickStore(const MemorySeries& series, int brick_size,
                   std::optional<tsp::ValueRange> range = {});
  const tsp::TspTree& tree() const override { return tree_; }
  void read_brick(int brick, int step, std::span<std::uint16_t> out) const override;
  /// Number of read_brick calls so far.
  std::int64_t reads() const { return reads_; }
  /// Makes every later read_brick throw tsp::IoError (error-path tests).
  void fail_reads(bool fail) { fail_ = fail; }
  /// The decoded (quantized) value of a sample, as the reference metric sees it.
  float decoded(int t, int x, int y, int z) const;

 private:
  MemorySeries series_;
  tsp::TspTree tree_;
  mutable std::atomic<std::int64_t> reads_{0};
  std::atomic<bool> fail_{false};
};

}  // namespace tsptest

// The reference colour metric (TSP paper §5.2, spec §4): every voxel classified through the TF,
// one pass over the bricks with expanded sums, multithreaded over bricks, and incremental: a
// brick whose entry range misses every entry changed since the previous update keeps its sums.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "tsp/metric/metric.h"
#include "tsp/store/brick_store.h"

namespace tsp {

/// Reference-metric state for one tree; update() after every TF edit.
class ReferenceMetric {
 public:
  /// Binds to bricks (which must outlive this object); computes nothing yet.
  explicit ReferenceMetric(const BrickStore& bricks);
  /// Brings every node up to date with tf using `threads` workers (0 = all cores) and returns
  /// how many leaf bricks were re-read. Throws what BrickStore::read_brick throws (the state
  /// then counts as never computed).
  int update(const TransferFunction& tf, int threads = 0);
  /// Result of TSP node id after the last update (transparency from the exact min/max test).
  NodeResult node(int id) const;
  /// Copies every node's result into out (resized to the tree).
  void fill(MetricResult& out) const;

  /// Per-node sums over the node's N samples: count N, voxels n, Σr, Σg, Σb, Σα, Σα², Σαr,
  /// Σαg, Σαb, Σα(r²+g²+b²), and Σᵢ σ̂ᵢ/f̂ᵢ over its voxels for e_t.
  struct Sums {
    double samples = 0, voxels = 0;
    std::array<double, 9> s{};
    double temporal = 0;
  };

 private:
  const BrickStore& bricks_;
  std::vector<Sums> sums_;                // per TSP node
  std::optional<TransferFunction> last_;  // TF of the previous update
  std::vector<std::uint8_t> transparent_;
  struct BrickScratch;
  void compute_brick(int brick, const std::vector<std::uint16_t>& lut, BrickScratch& scratch);
  void combine_internal_nodes();
};

}  // namespace tsp

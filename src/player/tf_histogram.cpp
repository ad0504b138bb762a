#include "player/tf_histogram.h"

#include <algorithm>
#include <cmath>

#include "tsp/tree/tsp_tree.h"

namespace tspplayer {

EditorHistogram editor_histogram(const tsp::BrickStore& bricks, int step, tsp::ValueRange over,
                                 int bins) {
  EditorHistogram h{over, std::vector<double>(std::size_t(std::max(1, bins)), 0.0), -1};
  const double span = over.hi > over.lo ? over.hi - over.lo : 1.0;
  const double n = double(h.counts.size());
  const tsp::TspTree& tree = bricks.tree();
  const tsp::ValueRange q = tree.value_range();
  const std::span<const std::uint64_t> stored = bricks.histogram();
  const double stored_bin = stored.empty() ? 0 : (q.hi - q.lo) / double(stored.size());
  if (!stored.empty() && stored_bin > 0 && span / stored_bin >= kMinStoredBins) {
    for (std::size_t i = 0; i < stored.size(); ++i) {  // each stored bin split by overlap
      const double v0 = q.lo + stored_bin * double(i), v1 = v0 + stored_bin;
      const double a = (v0 - over.lo) / span * n, b = (v1 - over.lo) / span * n;
      for (int k = std::max(0, int(std::floor(a))); k < std::min(int(n), int(std::ceil(b))); ++k) {
        const double overlap = std::min(b, double(k + 1)) - std::max(a, double(k));
        if (overlap > 0) h.counts[std::size_t(k)] += double(stored[i]) * overlap / (b - a);
      }
    }
    return h;
  }
  h.step = step;
  const tsp::Quantizer quant{q};
  const tsp::Octree& o = tree.octree();
  const int count = o.brick_count();
  const int stride = std::max(1, (count + kHistogramBricks - 1) / kHistogramBricks);
  std::vector<std::uint16_t> codes;
  std::vector<std::uint8_t> inside;
  for (int b = 0; b < count; b += stride) {
    if (!o.brick_present(b)) continue;
    codes.resize(std::size_t(o.lattice(b).count()));
    bricks.read_brick(b, step, codes);
    if (tree.has_stencil()) {
      inside.resize(codes.size());
      bricks.read_inside(b, step, inside);
    }
    for (std::size_t i = 0; i < codes.size(); ++i) {
      if (!inside.empty() && !inside[i]) continue;
      const double v = quant.decode(codes[i]);
      const double k = std::floor((v - over.lo) / span * n);
      if (k >= 0 && k < n) h.counts[std::size_t(k)] += 1;
      else if (v == over.hi) h.counts.back() += 1;
    }
  }
  return h;
}

}  // namespace tspplayer

// tsp/store: where bricks are kept — the .tsp file, this interface, the RAM cache and its
// prefetcher; may include core/, hdf5/ and tree/.
// Read access to quantized brick samples, one (brick, step) at a time.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>

#include "tsp/tree/tsp_tree.h"

namespace tsp {

/// Source of quantized brick samples: the leaf bricks and the LOD level bricks (stored brick
/// index, Octree::stored_brick_count()). Implemented by the .tsp file reader and by
/// in-memory stores in tests.
class BrickStore {
 public:
  virtual ~BrickStore() = default;
  /// The tree the bricks belong to.
  virtual const TspTree& tree() const = 0;
  /// The value histogram of every sample, equal bins over tree().value_range(); empty when the
  /// store has none. Never throws.
  virtual std::span<const std::uint64_t> histogram() const { return {}; }
  /// Reads stored brick b at step t into out: tree().octree().lattice(b).count() codes,
  /// x fastest. Throws IoError/FormatError.
  virtual void read_brick(int brick, int step, std::span<std::uint16_t> out) const = 0;
  /// Reads stored brick b's stencil at step t into out (lattice(b).count() bytes, 1 = inside
  /// the data); only called when tree().has_stencil(). Throws IoError/FormatError.
  virtual void read_inside(int brick, int step, std::span<std::uint8_t> out) const {
    (void)brick;
    (void)step;
    std::fill(out.begin(), out.end(), std::uint8_t(1));
  }
};

}  // namespace tsp

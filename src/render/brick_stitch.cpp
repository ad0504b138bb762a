// BrickTextures::stitch: the texels neighbouring bricks share, made to agree in every slot.
//
// A brick of n cells stores n + 1 samples per axis: its upper layers are its neighbours' first.
// When the tree draws two neighbours from textures of different steps (a brick coherent over a
// span reads its span's texture), each slot held its own step's copy of the shared layer, and a
// sample just below the face read one step's value or the other's depending on which brick the
// ray was in. The dense region of the CPU caster (place_dense) gives a shared texel the
// highest-numbered textured brick's sample; stitching gives every slot the same rule, so the GL
// caster, slices and the CPU caster's brick-by-brick walk read what the dense region reads.
#include <algorithm>
#include <unordered_map>
#include <vector>

#include "render/brick_textures.h"
#include "render/texture_samples.h"

namespace tspgl {
namespace detail {

/// The 13 neighbour offsets whose brick numbers are higher (x fastest, then y, then z), in
/// ascending order of those numbers.
constexpr std::array<std::array<int, 3>, 13> kHigherNeighbours{{{1, 0, 0},
                                                                {-1, 1, 0},
                                                                {0, 1, 0},
                                                                {1, 1, 0},
                                                                {-1, -1, 1},
                                                                {0, -1, 1},
                                                                {1, -1, 1},
                                                                {-1, 0, 1},
                                                                {0, 0, 1},
                                                                {1, 0, 1},
                                                                {-1, 1, 1},
                                                                {0, 1, 1},
                                                                {1, 1, 1}}};
constexpr int kNotTextured = -2;

/// True when keys a and b of neighbouring bricks hold the same step's samples (or the same
/// span's mean): then the texels they share agree.
inline bool same_samples(const tsp::TextureKey& a, const tsp::TextureKey& b) {
  return a.t0 == b.t0 && a.is_mean() == b.is_mean() && (!a.is_mean() || a.t1 == b.t1);
}

/// Copies the samples (codes, then `planes - 1` more planes such as stencil flags) of lattice
/// `from` that lie in lattice `to`'s box into `dst` (laid out as `to`). Never throws.
inline void copy_shared(const tsp::BrickLattice& from, const std::uint16_t* src,
                        const tsp::BrickLattice& to, std::uint16_t* dst, int planes) {
  std::array<int, 3> lo{}, hi{};
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::max(from.origin[a], to.origin[a]);
    hi[a] = std::min(from.origin[a] + from.samples[a], to.origin[a] + to.samples[a]);
    if (hi[a] <= lo[a]) return;
  }
  const std::int64_t from_count = from.count(), to_count = to.count();
  for (int p = 0; p < planes; ++p)
    for (int z = lo[2]; z < hi[2]; ++z)
      for (int y = lo[1]; y < hi[1]; ++y) {
        const std::int64_t s =
            p * from_count + (lo[0] - from.origin[0]) +
            std::int64_t(from.samples[0]) *
                ((y - from.origin[1]) + std::int64_t(from.samples[1]) * (z - from.origin[2]));
        const std::int64_t d =
            p * to_count + (lo[0] - to.origin[0]) +
            std::int64_t(to.samples[0]) *
                ((y - to.origin[1]) + std::int64_t(to.samples[1]) * (z - to.origin[2]));
        std::copy_n(src + s, hi[0] - lo[0], dst + d);
      }
}

}  // namespace detail

std::int64_t BrickTextures::slot_bytes(const tsp::BrickLattice& s) const {
  return s.count() * channels_ * std::int64_t(sizeof(std::uint16_t));
}

std::int64_t BrickTextures::stitch(const std::vector<tsp::TextureKey>& level0) {
  if (!atlas_) return 0;
  const std::vector<tsp::TextureKey> want = by_brick(level0);
  if (want.empty()) return 0;
  const tsp::Octree& octree = bricks_.store().tree().octree();
  const auto g = octree.brick_grid();
  auto textured = [&](int b) { return want[std::size_t(b)].level == 0; };
  // Each brick's samples read once in this call (a neighbour serves up to 13 slots; a span's
  // mean is computed, not cached).
  std::unordered_map<int, tsp::BrickSamples> read;
  auto samples_of = [&](int b) -> const tsp::BrickSamples& {
    auto it = read.find(b);
    if (it == read.end()) it = read.emplace(b, texture_samples(bricks_, want[std::size_t(b)])).first;
    return it->second;
  };
  std::vector<std::uint16_t> buffer;
  std::int64_t bytes = 0;
  for (int b = 0; b < int(want.size()); ++b) {
    if (!textured(b)) continue;
    const tsp::TextureKey& key = want[std::size_t(b)];
    const std::array<int, 3> c{b % g[0], b / g[0] % g[1], b / (g[0] * g[1])};
    StitchSteps steps{};
    std::array<int, 13> neighbour{};
    bool differs = false;  // some textured neighbour holds another step's samples
    for (std::size_t i = 0; i < detail::kHigherNeighbours.size(); ++i) {
      const auto& d = detail::kHigherNeighbours[i];
      const std::array<int, 3> n{c[0] + d[0], c[1] + d[1], c[2] + d[2]};
      neighbour[i] = -1;
      steps[i] = {detail::kNotTextured, detail::kNotTextured};
      if (n[0] < 0 || n[1] < 0 || n[0] >= g[0] || n[1] >= g[1] || n[2] >= g[2]) continue;
      const int nb = n[0] + g[0] * (n[1] + g[1] * n[2]);
      if (!textured(nb)) continue;
      const tsp::TextureKey& nk = want[std::size_t(nb)];
      neighbour[i] = nb;
      steps[i] = {nk.t0, nk.t1};
      differs |= !detail::same_samples(nk, key);
    }
    const int slot = slots_.at(key);
    const auto held = stitched_.find(slot);
    const bool was_modified = held != stitched_.end() && held->second.modified;
    const tsp::BrickLattice own = octree.lattice(b);
    if (!differs) {  // every sharer holds this step: the brick's own samples are right
      if (was_modified) {
        put(slot, own, samples_of(b)->data());
        bytes += slot_bytes(own);
      }
      stitched_.erase(slot);
      continue;
    }
    if (held != stitched_.end() && held->second.steps == steps) continue;
    const tsp::BrickSamples& samples = samples_of(b);
    buffer.assign(samples->begin(), samples->end());
    for (int nb : neighbour)  // ascending: the highest one wins
      if (nb >= 0)
        detail::copy_shared(octree.lattice(nb), samples_of(nb)->data(), own, buffer.data(),
                            channels_);  // (codes, and the stencil's flags)
    // (Steps whose samples agree on the faces, such as a field's still parts, change nothing.)
    const bool modified = !std::equal(buffer.begin(), buffer.end(), samples->begin());
    if (modified || was_modified) {
      put(slot, own, buffer.data());
      bytes += slot_bytes(own);
    }
    stitched_[slot] = Stitched{steps, modified};
  }
  return bytes;
}

}  // namespace tspgl

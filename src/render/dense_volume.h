// The whole volume in one texture, each leaf brick at its own place (neighbours write the same
// shared layer), kept up to date brick by brick from the RAM brick cache. When a frame textures
// every leaf brick at full resolution — nothing transparent to leap, nothing coherent to draw
// flat: a filled TF over turbulence — the one-pass ray caster walks this one "brick" as the
// non-TSP baseline does, instead of the brick grid: on a SIMD rasteriser (llvmpipe) rays that
// cross brick faces at different samples diverge, and the grid walk cost a quarter more than the
// whole volume (docs/rendering.md). Partial-image reuse and the texture cache are unchanged.
#pragma once
#include <cstdint>
#include <vector>

#include "render/brick_textures.h"
#include "tsp/frame/texture_cache.h"
#include "tsp/store/brick_cache.h"

namespace tspgl {

/// One texture of the volume's size holding, per leaf brick, the samples of one texture key.
/// Use from the context's thread with it current; not copyable.
class DenseVolume {
 public:
  /// Nothing is allocated until the first update; bricks must outlive it.
  DenseVolume(const GlApi& gl, tsp::BrickCache& bricks);
  ~DenseVolume();
  DenseVolume(const DenseVolume&) = delete;
  DenseVolume& operator=(const DenseVolume&) = delete;

  /// Makes leaf brick b hold keys[b]'s samples (level-0 keys, one per leaf brick; brick −1: not
  /// sampled this frame, left as it is), writing only the bricks whose key changed since the
  /// last update. Returns the bytes written. Throws what the brick store throws,
  /// tsp::GlError.
  std::int64_t update(const std::vector<tsp::TextureKey>& keys);
  /// The texture as a slot for the whole volume (sample p at texel p).
  BrickSlot slot() const;
  /// Forgets what it holds (the next update writes every brick).
  void clear() { held_.clear(); }
  /// Keeps a copy in RAM for the CPU ray caster (BrickSlot::host) from the next update on;
  /// turning it on or off makes the next update write every brick.
  void set_host_mirror(bool on) {
    if (on == mirror_) return;
    mirror_ = on;
    host_ = HostVolume{};
    held_.clear();
  }

 private:
  const GlApi& gl_;
  tsp::BrickCache& bricks_;
  GLuint texture_ = 0;
  int channels_ = 1;
  bool mirror_ = false;  ///< host_ mirrors the texture
  HostVolume host_;
  std::vector<tsp::TextureKey> held_;  ///< per leaf brick; brick −1: nothing yet
  std::vector<std::uint16_t> texels_;
};

}  // namespace tspgl

#include "render/dense_volume.h"

#include <cassert>

#include "gl/gl_error.h"
#include "render/texture_samples.h"

namespace tspgl {

DenseVolume::DenseVolume(const GlApi& gl, tsp::BrickCache& bricks) : gl_(gl), bricks_(bricks) {
  channels_ = bricks_.store().tree().has_stencil() ? 2 : 1;
}

DenseVolume::~DenseVolume() {
  if (texture_) gl_.DeleteTextures(1, &texture_);
}

std::int64_t DenseVolume::update(const std::vector<tsp::TextureKey>& keys) {
  const tsp::Octree& o = bricks_.store().tree().octree();
  assert(int(keys.size()) == o.brick_count());
  if (!texture_) {
    const tsp::Dims d = o.dims();
    texture_ = create_scalar_texture(gl_, d.x, d.y, d.z, nullptr, channels_);
    check_gl(gl_, "allocating the dense volume texture");
  }
  if (mirror_ && host_.empty()) {
    const tsp::Dims d = o.dims();
    host_.allocate(d.x, d.y, d.z, channels_);
  }
  if (held_.size() != keys.size()) held_.assign(keys.size(), tsp::TextureKey{-1, -1, -1});
  std::int64_t bytes = 0;
  gl_.BindTexture(GL_TEXTURE_3D, texture_);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int b = 0; b < o.brick_count(); ++b) {
    const tsp::TextureKey& k = keys[std::size_t(b)];
    if (k.brick < 0) continue;  // not sampled this frame (clipped away): left as it is
    assert(k.brick == b && k.level == 0);
    if (held_[std::size_t(b)] == k) continue;
    tsp::BrickSamples samples = texture_samples(bricks_, k);
    const tsp::Box s = o.brick_samples(b);
    const std::uint16_t* texels = samples->data();
    if (channels_ == 2) {
      interleave_stencil(samples->data(), std::size_t(s.count()), texels_);
      texels = texels_.data();
    }
    if (mirror_) host_.write({s.lo[0], s.lo[1], s.lo[2]}, s.size(0), s.size(1), s.size(2), texels);
    gl_.TexSubImage3D(GL_TEXTURE_3D, 0, s.lo[0], s.lo[1], s.lo[2], s.size(0), s.size(1), s.size(2),
                      channels_ == 2 ? GL_RG : GL_RED, GL_UNSIGNED_SHORT, texels);
    held_[std::size_t(b)] = k;
    bytes += s.count() * std::int64_t(sizeof(std::uint16_t)) * channels_;
  }
  return bytes;
}

BrickSlot DenseVolume::slot() const {
  const tsp::Dims d = bricks_.store().tree().octree().dims();
  return BrickSlot{texture_, {0.5f, 0.5f, 0.5f}, {d.x, d.y, d.z}, {1, 1, 1},
                   mirror_ ? &host_ : nullptr};
}

}  // namespace tspgl

// GL textures of quantized scalars: the one creator of 16-bit scalar textures (bricks and the
// baseline's whole volume), and the GL side of the TextureCache policy — one texture object per
// resident TextureKey, filled from the RAM brick cache.
#pragma once
#include <cstdint>
#include <unordered_map>

#include "gl/gl_api.h"
#include "tsp/frame/texture_cache.h"
#include "tsp/store/brick_cache.h"

namespace tspgl {

/// A new trilinear, edge-clamped R16 3-D texture of w × h × d samples (x fastest), bound to
/// GL_TEXTURE_3D of the active unit. The caller owns it.
GLuint create_scalar_texture(const GlApi& gl, int w, int h, int d, const std::uint16_t* data);

/// Brick textures by key. Use from the context's thread with it current; not copyable.
class BrickTextures {
 public:
  /// Textures of the bricks in bricks (which must outlive this object).
  BrickTextures(const GlApi& gl, tsp::BrickCache& bricks) : gl_(gl), bricks_(bricks) {}
  /// Deletes every texture.
  ~BrickTextures() { clear(); }
  BrickTextures(const BrickTextures&) = delete;
  BrickTextures& operator=(const BrickTextures&) = delete;

  /// Reads key's brick at key.t0 through the brick cache and (re)creates its texture. Throws
  /// what the brick store throws.
  GLuint upload(const tsp::TextureKey& key);
  /// The texture of a resident key (asserts it is resident).
  GLuint at(const tsp::TextureKey& key) const;
  /// True when key has a texture.
  bool contains(const tsp::TextureKey& key) const { return ids_.contains(key); }
  /// Deletes key's texture, if any.
  void erase(const tsp::TextureKey& key);
  /// Deletes every texture.
  void clear();
  /// Number of textures alive.
  int size() const { return int(ids_.size()); }

 private:
  const GlApi& gl_;
  tsp::BrickCache& bricks_;
  std::unordered_map<tsp::TextureKey, GLuint, tsp::TextureKeyHash> ids_;
};

}  // namespace tspgl

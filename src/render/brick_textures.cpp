#include "render/brick_textures.h"

#include <cassert>

namespace tspgl {

GLuint create_scalar_texture(const GlApi& gl, int w, int h, int d, const std::uint16_t* data) {
  GLuint id = 0;
  gl.GenTextures(1, &id);
  gl.BindTexture(GL_TEXTURE_3D, id);
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    gl.TexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
  // 16-bit rows of odd width are not 4-byte aligned.
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.TexImage3D(GL_TEXTURE_3D, 0, GL_R16, w, h, d, 0, GL_RED, GL_UNSIGNED_SHORT, data);
  return id;
}

GLuint BrickTextures::upload(const tsp::TextureKey& key) {
  erase(key);
  tsp::BrickSamples samples = bricks_.get(key.brick, key.t0);
  const tsp::Box s = bricks_.store().tree().octree().brick_samples(key.brick);
  const GLuint id = create_scalar_texture(gl_, s.size(0), s.size(1), s.size(2), samples->data());
  ids_[key] = id;
  return id;
}

GLuint BrickTextures::at(const tsp::TextureKey& key) const {
  auto it = ids_.find(key);
  assert(it != ids_.end() && "brick texture not resident");
  return it->second;
}

void BrickTextures::erase(const tsp::TextureKey& key) {
  auto it = ids_.find(key);
  if (it == ids_.end()) return;
  gl_.DeleteTextures(1, &it->second);
  ids_.erase(it);
}

void BrickTextures::clear() {
  for (auto& [key, id] : ids_) gl_.DeleteTextures(1, &id);
  ids_.clear();
}

}  // namespace tspgl

#include "render/brick_textures.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "gl/gl_error.h"
#include "render/texture_samples.h"

namespace tspgl {
namespace {

// The atlas first holds every leaf brick, or as many as this much texture when they need more
// (an adaptive file's finest grid may hold thousands of bricks it never draws); it doubles as
// needed.
constexpr std::int64_t kFirstAtlasBytes = std::int64_t(256) << 20;

}  // namespace

void interleave_stencil(const std::uint16_t* samples, std::size_t count,
                        std::vector<std::uint16_t>& out) {
  out.resize(2 * count);
  for (std::size_t i = 0; i < count; ++i) {
    out[2 * i] = samples[i];
    out[2 * i + 1] = samples[count + i] ? 65535 : 0;
  }
}

GLuint create_scalar_texture(const GlApi& gl, int w, int h, int d, const std::uint16_t* data,
                             int channels) {
  GLuint id = 0;
  gl.GenTextures(1, &id);
  gl.BindTexture(GL_TEXTURE_3D, id);
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    gl.TexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
  // 16-bit rows of odd width are not 4-byte aligned.
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (channels == 2)
    gl.TexImage3D(GL_TEXTURE_3D, 0, GL_RG16, w, h, d, 0, GL_RG, GL_UNSIGNED_SHORT, data);
  else
    gl.TexImage3D(GL_TEXTURE_3D, 0, GL_R16, w, h, d, 0, GL_RED, GL_UNSIGNED_SHORT, data);
  return id;
}

BrickTextures::BrickTextures(const GlApi& gl, tsp::BrickCache& bricks) : gl_(gl), bricks_(bricks) {
  slot_ = bricks_.store().tree().octree().max_brick_samples();
  channels_ = bricks_.store().tree().has_stencil() ? 2 : 1;
}

BrickTextures::~BrickTextures() {
  if (atlas_) gl_.DeleteTextures(1, &atlas_);
}

std::array<int, 3> BrickTextures::slot_origin(int slot) const {
  return {slot % grid_[0] * slot_[0], slot / grid_[0] % grid_[1] * slot_[1],
          slot / (grid_[0] * grid_[1]) * slot_[2]};
}

void BrickTextures::write(const tsp::TextureKey& key, int slot) {
  tsp::BrickSamples samples = texture_samples(bricks_, key);
  const tsp::BrickLattice s = bricks_.store().tree().octree().lattice(key.brick);
  const auto o = slot_origin(slot);
  gl_.BindTexture(GL_TEXTURE_3D, atlas_);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  const std::uint16_t* texels = samples->data();
  if (channels_ == 2) {
    interleave_stencil(samples->data(), std::size_t(s.count()), texels_);
    texels = texels_.data();
  }
  if (mirror_) host_.write(o, s.samples[0], s.samples[1], s.samples[2], texels);
  gl_.TexSubImage3D(GL_TEXTURE_3D, 0, o[0], o[1], o[2], s.samples[0], s.samples[1], s.samples[2],
                    channels_ == 2 ? GL_RG : GL_RED, GL_UNSIGNED_SHORT, texels);
  slots_[key] = slot;
}

void BrickTextures::grow(int min_capacity) {
  GLint max_size = 0;
  gl_.GetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max_size);
  // Near-cubic slot grids: n³ slots with n the smallest edge that holds min_capacity.
  const int n = std::max(1, int(std::ceil(std::cbrt(double(min_capacity)) - 1e-9)));
  std::array<int, 3> grid{n, n, n};
  while ((grid[0] * grid[1] * (grid[2] - 1)) >= min_capacity) --grid[2];
  for (int a = 0; a < 3; ++a)
    if (std::int64_t(grid[a]) * slot_[a] > max_size)
      throw tsp::GlError("brick atlas: " + std::to_string(min_capacity) + " bricks of " +
                    std::to_string(slot_[0]) + "x" + std::to_string(slot_[1]) + "x" +
                    std::to_string(slot_[2]) + " samples need a 3-D texture beyond " +
                    "GL_MAX_3D_TEXTURE_SIZE " + std::to_string(max_size) +
                    "; lower --texture-budget");
  std::vector<tsp::TextureKey> resident;
  resident.reserve(slots_.size());
  for (const auto& [key, slot] : slots_) resident.push_back(key);
  if (atlas_) gl_.DeleteTextures(1, &atlas_);
  grid_ = grid;
  atlas_ = create_scalar_texture(gl_, grid[0] * slot_[0], grid[1] * slot_[1], grid[2] * slot_[2],
                                 nullptr, channels_);
  check_gl(gl_, "allocating the brick atlas");
  if (mirror_)
    host_.allocate(grid[0] * slot_[0], grid[1] * slot_[1], grid[2] * slot_[2], channels_);
  slots_.clear();
  free_.clear();
  for (int s = capacity() - 1; s >= int(resident.size()); --s) free_.push_back(s);
  for (std::size_t i = 0; i < resident.size(); ++i) write(resident[i], int(i));
}

void BrickTextures::upload(const tsp::TextureKey& key) {
  auto it = slots_.find(key);
  if (it != slots_.end()) {
    write(key, it->second);
    return;
  }
  if (free_.empty()) {
    const std::int64_t slot_bytes =
        std::int64_t(slot_[0]) * slot_[1] * slot_[2] * std::int64_t(sizeof(std::uint16_t)) * channels_;
    const std::int64_t first = std::min<std::int64_t>(bricks_.store().tree().octree().brick_count(),
                                                      std::max<std::int64_t>(1, kFirstAtlasBytes / slot_bytes));
    grow(std::max(2 * capacity(), int(first)));
  }
  const int slot = free_.back();
  free_.pop_back();
  write(key, slot);
}

BrickSlot BrickTextures::at(const tsp::TextureKey& key) const {
  auto it = slots_.find(key);
  assert(it != slots_.end() && "brick texture not resident");
  const tsp::BrickLattice s = bricks_.store().tree().octree().lattice(key.brick);
  const auto o = slot_origin(it->second);
  BrickSlot b;
  b.texture = atlas_;
  for (int a = 0; a < 3; ++a) {
    // texel = (p − origin)/factor + slot origin + ½ (texel centres).
    b.scale[a] = 1.f / float(s.factor[a]);
    b.offset[a] = float(o[a]) + 0.5f - float(s.origin[a]) * b.scale[a];
    b.atlas_size[a] = grid_[a] * slot_[a];
  }
  b.host = mirror_ ? &host_ : nullptr;
  return b;
}

void BrickTextures::set_host_mirror(bool on) {
  if (on == mirror_) return;
  mirror_ = on;
  if (!on) {
    host_ = HostVolume{};
    return;
  }
  if (!atlas_) return;  // allocated with the atlas
  host_.allocate(grid_[0] * slot_[0], grid_[1] * slot_[1], grid_[2] * slot_[2], channels_);
  // Residents in slot order: the same copy whatever the map's order.
  std::vector<std::pair<int, tsp::TextureKey>> resident;
  for (const auto& [key, slot] : slots_) resident.emplace_back(slot, key);
  std::sort(resident.begin(), resident.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [slot, key] : resident) write(key, slot);
}

void BrickTextures::erase(const tsp::TextureKey& key) {
  auto it = slots_.find(key);
  if (it == slots_.end()) return;
  free_.push_back(it->second);
  slots_.erase(it);
  variations_.erase(key);
}

void BrickTextures::clear() {
  for (const auto& [key, slot] : slots_) free_.push_back(slot);
  slots_.clear();
  variations_.clear();
}

const tsp::CellVariations& BrickTextures::variations(
    const tsp::TextureKey& key, const std::function<tsp::CellVariations()>& make) {
  assert(contains(key) && "variations of a texture not resident");
  auto it = variations_.find(key);
  if (it == variations_.end()) it = variations_.emplace(key, make()).first;
  return it->second;
}

}  // namespace tspgl

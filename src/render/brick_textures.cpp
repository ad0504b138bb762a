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
  put(slot, bricks_.store().tree().octree().lattice(key.brick), samples->data());
  slots_[key] = slot;
  stitched_.erase(slot);  // its own samples again
}

void BrickTextures::put(int slot, const tsp::BrickLattice& s, const std::uint16_t* samples) {
  const auto o = slot_origin(slot);
  gl_.BindTexture(GL_TEXTURE_3D, atlas_);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  const std::uint16_t* texels = samples;
  if (channels_ == 2) {
    interleave_stencil(samples, std::size_t(s.count()), texels_);
    texels = texels_.data();
  }
  if (mirror_) host_.write(o, s.samples[0], s.samples[1], s.samples[2], texels);
  gl_.TexSubImage3D(GL_TEXTURE_3D, 0, o[0], o[1], o[2], s.samples[0], s.samples[1], s.samples[2],
                    channels_ == 2 ? GL_RG : GL_RED, GL_UNSIGNED_SHORT, texels);
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
  if (mirror_) allocate_host();
  slots_.clear();
  stitched_.clear();
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
  allocate_host();
  // Residents in slot order: the same copy whatever the map's order.
  std::vector<std::pair<int, tsp::TextureKey>> resident;
  for (const auto& [key, slot] : slots_) resident.emplace_back(slot, key);
  std::sort(resident.begin(), resident.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [slot, key] : resident) write(key, slot);
}

std::array<int, 3> BrickTextures::dense_size() const {
  const tsp::Octree& octree = bricks_.store().tree().octree();
  const auto g = octree.brick_grid();
  return {g[0] * octree.brick_cells(0) + 1, g[1] * octree.brick_cells(1) + 1,
          g[2] * octree.brick_cells(2) + 1};
}

// The slots' texels where the atlas has them, then (when it fits) the dense region after them.
void BrickTextures::allocate_host() {
  const std::array<int, 3> atlas{grid_[0] * slot_[0], grid_[1] * slot_[1], grid_[2] * slot_[2]};
  const auto dense = dense_size();
  const std::int64_t dense_bytes = std::int64_t(dense[0]) * dense[1] * dense[2] * 2 * channels_;
  placed_.assign(std::size_t(bricks_.store().tree().octree().brick_count()), tsp::TextureKey{});
  for (auto& k : placed_) k.level = -1;
  if (dense_bytes > kMaxDenseHostBytes) {
    dense_z_ = -1;
    host_.allocate(atlas[0], atlas[1], atlas[2], channels_);
    return;
  }
  dense_z_ = atlas[2];
  host_.allocate(std::max(atlas[0], dense[0]), std::max(atlas[1], dense[1]), atlas[2] + dense[2],
                 channels_);
}

std::vector<tsp::TextureKey> BrickTextures::by_brick(const std::vector<tsp::TextureKey>& level0) const {
  const tsp::Octree& octree = bricks_.store().tree().octree();
  const int count = octree.brick_count();
  std::vector<tsp::TextureKey> want(static_cast<std::size_t>(count));
  for (auto& k : want) k.level = -1;
  for (const tsp::TextureKey& k : level0) {
    if (k.level != 0 || k.brick < 0 || k.brick >= count || !contains(k)) return {};
    if (octree.lattice(k.brick).factor != std::array<int, 3>{1, 1, 1}) return {};
    tsp::TextureKey& w = want[std::size_t(k.brick)];
    if (w.level == 0 && !(w == k)) return {};  // two keys of one brick
    w = k;
  }
  return want;
}

bool BrickTextures::place_dense(const std::vector<tsp::TextureKey>& level0) {
  if (!mirror_ || !atlas_ || dense_z_ < 0) return false;
  const tsp::Octree& octree = bricks_.store().tree().octree();
  const int count = octree.brick_count();
  std::vector<tsp::TextureKey> want = by_brick(level0);
  if (want.empty()) return false;  // the slots alone
  const auto g = octree.brick_grid();
  auto placed = [&](int b) { return want[std::size_t(b)].level == 0; };
  // Brick b's samples (its key's slot) over the box `lo`..`hi` of the volume's samples.
  auto copy = [&](int b, std::array<int, 3> lo, std::array<int, 3> hi) {
    const tsp::BrickLattice l = octree.lattice(b);
    const auto o = slot_origin(slots_.at(want[std::size_t(b)]));
    std::array<int, 3> from{}, to{}, box{};
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(lo[a], l.origin[a]);
      hi[a] = std::min(hi[a], l.origin[a] + l.samples[a]);
      if (hi[a] <= lo[a]) return;
      from[a] = o[a] + lo[a] - l.origin[a];
      to[a] = lo[a];
      box[a] = hi[a] - lo[a];
    }
    to[2] += dense_z_;
    host_.copy_within(from, to, box);
  };
  auto whole = [&](int b) {
    const tsp::BrickLattice l = octree.lattice(b);
    return std::pair{l.origin, std::array<int, 3>{l.origin[0] + l.samples[0], l.origin[1] + l.samples[1],
                                                  l.origin[2] + l.samples[2]}};
  };
  std::vector<int> changed;
  for (int b = 0; b < count; ++b)
    if (!(want[std::size_t(b)] == placed_[std::size_t(b)])) changed.push_back(b);
  for (int b : changed)  // ascending: a higher brick's shared texels win among the changed
    if (placed(b)) copy(b, whole(b).first, whole(b).second);
  // Each changed brick's texels shared with a neighbour: the highest textured one's samples.
  for (int b : changed) {
    const std::array<int, 3> c{b % g[0], b / g[0] % g[1], b / (g[0] * g[1])};
    const auto [lo, hi] = whole(b);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const std::array<int, 3> n{c[0] + dx, c[1] + dy, c[2] + dz};
          if ((dx | dy | dz) == 0 || n[0] < 0 || n[1] < 0 || n[2] < 0 || n[0] >= g[0] ||
              n[1] >= g[1] || n[2] >= g[2])
            continue;
          const int nb = n[0] + g[0] * (n[1] + g[1] * n[2]);
          if (placed(nb) && (nb > b || !placed(b))) copy(nb, lo, hi);
        }
  }
  placed_ = std::move(want);
  return true;
}

BrickSlot BrickTextures::dense_at(const tsp::TextureKey& key) const {
  assert(key.brick >= 0 && std::size_t(key.brick) < placed_.size() &&
         placed_[std::size_t(key.brick)] == key && "brick not placed in the dense region");
  BrickSlot b = at(key);
  // Sample p sits at texel p (+ the region's first slice along z); texel centres at +½.
  b.offset = {0.5f, 0.5f, float(dense_z_) + 0.5f};
  return b;
}

void BrickTextures::erase(const tsp::TextureKey& key) {
  auto it = slots_.find(key);
  if (it == slots_.end()) return;
  free_.push_back(it->second);
  stitched_.erase(it->second);
  slots_.erase(it);
  variations_.erase(key);
}

void BrickTextures::clear() {
  for (const auto& [key, slot] : slots_) free_.push_back(slot);
  slots_.clear();
  stitched_.clear();
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

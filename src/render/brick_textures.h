// GL textures of quantized scalars: the one creator of 16-bit scalar textures (the brick atlas
// and the baseline's whole volume), and the GL side of the TextureCache policy — every resident
// TextureKey owns one slot of a single 3-D atlas texture, filled from the RAM brick cache. One
// atlas lets a ray caster walk from brick to brick in one pass; slicing samples the same slots.
// What the renderer derives from a resident texture's samples (adaptive sampling's cell
// variations) lives here too, and leaves with the slot: one eviction rule.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

#include "gl/gl_api.h"
#include "render/host_volume.h"
#include "tsp/frame/sample_steps.h"
#include "tsp/frame/texture_cache.h"
#include "tsp/store/brick_cache.h"

namespace tspgl {

/// A new trilinear, edge-clamped R16 3-D texture of w × h × d samples (x fastest; data may be
/// null: contents undefined), bound to GL_TEXTURE_3D of the active unit; with channels 2 an
/// RG16 texture (data interleaved: code, stencil 0 or 65535). The caller owns it.
GLuint create_scalar_texture(const GlApi& gl, int w, int h, int d, const std::uint16_t* data,
                             int channels = 1);
/// Interleaves a stencilled BrickSamples (count codes, then count flags) into RG16 texels
/// (code, flag · 65535) in out. Never throws.
void interleave_stencil(const std::uint16_t* samples, std::size_t count,
                        std::vector<std::uint16_t>& out);

/// Where a resident brick's samples are: sample coordinate p of the volume reads atlas texel
/// coordinate p + offset (texel centres at +½), i.e. texture coordinate (p + offset) / size.
struct BrickSlot {
  GLuint texture = 0;                ///< the atlas
  std::array<float, 3> offset{};     ///< atlas texel coordinate − sample coordinate · scale
  std::array<int, 3> atlas_size{};   ///< atlas extent in texels
  std::array<float, 3> scale{1, 1, 1};  ///< texels per voxel: 1 / the brick's LOD factor
  /// The texture's texels in RAM for the CPU ray caster (null: GL only; see set_host_mirror).
  const HostVolume* host = nullptr;
};

/// Brick textures by key, as slots of one atlas that grows (doubling, re-uploading the residents
/// from the brick cache) when full. Use from the context's thread with it current; not copyable.
class BrickTextures {
 public:
  /// Slots for the bricks in bricks (which must outlive this object); no atlas until the first
  /// upload.
  BrickTextures(const GlApi& gl, tsp::BrickCache& bricks);
  /// Deletes the atlas.
  ~BrickTextures();
  BrickTextures(const BrickTextures&) = delete;
  BrickTextures& operator=(const BrickTextures&) = delete;

  /// Reads key's brick at key.t0 through the brick cache into a slot (its own if resident).
  /// Growing the atlas moves every slot: call at() only after the frame's uploads. Throws what
  /// the brick store throws, tsp::GlError when the atlas would exceed GL_MAX_3D_TEXTURE_SIZE.
  void upload(const tsp::TextureKey& key);
  /// The slot of a resident key (asserts it is resident).
  BrickSlot at(const tsp::TextureKey& key) const;
  /// True when key has a slot.
  bool contains(const tsp::TextureKey& key) const { return slots_.contains(key); }
  /// Frees key's slot, if any, and forgets its variations.
  void erase(const tsp::TextureKey& key);
  /// Frees every slot (keeps the atlas) and forgets every variations.
  void clear();
  /// Adaptive sampling's cell variations of resident key: made by make() on first use and kept
  /// until key's slot is freed (erase, clear) or forget_variations(). Asserts key is resident;
  /// throws what make throws.
  const tsp::CellVariations& variations(const tsp::TextureKey& key,
                                        const std::function<tsp::CellVariations()>& make);
  /// Forgets every key's variations (a new transfer function); keeps the slots.
  void forget_variations() { variations_.clear(); }
  /// Number of resident keys whose variations are kept (never more than size()).
  int variations_count() const { return int(variations_.size()); }
  /// Number of resident keys.
  int size() const { return int(slots_.size()); }
  /// Keeps (on) or drops (off) a copy of the atlas in RAM that the CPU ray caster reads
  /// (BrickSlot::host); turning it on copies every resident brick. Throws what the brick store
  /// throws.
  void set_host_mirror(bool on);
  /// Slots the atlas holds now.
  int capacity() const { return grid_[0] * grid_[1] * grid_[2]; }
  /// The CPU ray caster's dense layout (with the host mirror on): copies the frame's level-0
  /// keys (resident, at most one per brick) from their slots to their bricks' own places in a
  /// region of the RAM copy laid out as the volume, so neighbouring bricks' texels sit side by
  /// side and a ray reads a run of them as one volume. A texel two bricks share holds the
  /// higher-numbered textured brick's sample, whatever the frames before (only the bricks whose
  /// key changed are copied again). False, changing nothing, without the mirror or when that
  /// region would pass kMaxDenseHostBytes. Never throws but std::bad_alloc.
  bool place_dense(const std::vector<tsp::TextureKey>& level0);
  /// Where a key placed by the last place_dense reads its texels in RAM (BrickSlot::host; the
  /// offset is not the GL atlas'). Asserts it is placed.
  BrickSlot dense_at(const tsp::TextureKey& key) const;
  /// Makes the texels that a frame's level-0 keys (resident, at most one per brick) share agree
  /// in every slot, as the dense region has them: a texel that textured bricks share holds the
  /// highest-numbered one's sample, so a brick drawn from another step's texture reads its
  /// neighbours' samples on its upper faces (both back ends). Rewrites (GL and the RAM copy)
  /// only the slots whose neighbours' steps changed since they were written; returns the bytes
  /// rewritten. Changes nothing (0) for two keys of one brick or an adaptive file's coarse
  /// leaves. Throws what the brick store throws.
  std::int64_t stitch(const std::vector<tsp::TextureKey>& level0);
  /// Largest dense region place_dense makes, in bytes (beyond: the slots alone).
  static constexpr std::int64_t kMaxDenseHostBytes = std::int64_t(1) << 30;

 private:
  const GlApi& gl_;
  tsp::BrickCache& bricks_;
  std::array<int, 3> slot_{};  ///< texels per slot (the largest brick)
  int channels_ = 1;           ///< 2 when the bricks carry a stencil (RG16 atlas)
  std::vector<std::uint16_t> texels_;  ///< interleaving buffer for stencilled uploads
  std::array<int, 3> grid_{};  ///< slots per axis
  GLuint atlas_ = 0;
  bool mirror_ = false;  ///< host_ mirrors the atlas
  HostVolume host_;
  std::vector<int> free_;      ///< free slot indices (popped from the back)
  std::unordered_map<tsp::TextureKey, int, tsp::TextureKeyHash> slots_;
  std::unordered_map<tsp::TextureKey, tsp::CellVariations, tsp::TextureKeyHash>
      variations_;  ///< per resident key, under the caller's TF
  /// Per leaf brick, the key place_dense put at its place (level −1: none).
  std::vector<tsp::TextureKey> placed_;
  int dense_z_ = 0;  ///< the dense region's first texel slice in host_ (after the slots')
  /// The steps (t0, t1; −2: not textured) of a brick's 13 higher-numbered neighbours.
  using StitchSteps = std::array<std::array<int, 2>, 13>;
  /// What stitch() made of a slot: the neighbours' steps it was stitched for, and whether its
  /// texels differ from the brick's own samples.
  struct Stitched {
    StitchSteps steps{};
    bool modified = false;
  };
  /// Per slot that stitch() saw with a neighbour of another step.
  std::unordered_map<int, Stitched> stitched_;
  /// The frame's level-0 keys (resident, full resolution) by brick (level −1: none); empty for
  /// two keys of one brick, an adaptive file's coarse leaf or a key not resident.
  std::vector<tsp::TextureKey> by_brick(const std::vector<tsp::TextureKey>& level0) const;
  /// Bytes a slot holding lattice s takes (both channels with a stencil).
  std::int64_t slot_bytes(const tsp::BrickLattice& s) const;
  /// Writes a brick's samples (codes, then stencil flags) to slot, in GL and the RAM copy.
  void put(int slot, const tsp::BrickLattice& s, const std::uint16_t* samples);
  void grow(int min_capacity);
  void allocate_host();
  std::array<int, 3> dense_size() const;
  void write(const tsp::TextureKey& key, int slot);
  std::array<int, 3> slot_origin(int slot) const;
};

}  // namespace tspgl

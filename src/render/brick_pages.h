// The one-pass ray caster's brick pages: per brick of the grid it walks, what the ray finds
// there (textured: where its texels are and at which LOD level and TF row; flat: one colour;
// empty: how far it may leap), as the texels of a small 3-D texture (GL) or array (CPU).
#pragma once
#include <array>
#include <vector>

#include "render/brick_textures.h"
#include "render/ray_constants.h"
#include "tsp/metric/transfer_function.h"

namespace tspgl {

/// ln(1 − α) of a flat colour's opacity per voxel (α clamped below 1 so it stays finite): what
/// the flat shaders and flat pages exponentiate. Never throws.
float log_transmittance(float alpha);

/// What the one-pass ray caster finds in each brick of the grid it walks (the TSP renderer's
/// frame plan, or the baseline's single "brick", the whole volume).
class BrickPages {
 public:
  /// Opacity per voxel below which a flat brick is drawn as empty (invisible at any depth the
  /// limits allow: 1 − (1 − 1e-7)^65536 < 0.01).
  static constexpr float kMinFlatAlpha = 1e-7f;
  /// Largest log2 LOD factor per axis a textured page encodes (factor 128).
  static constexpr int kMaxPageLevel = 7;
  /// Largest leap radius, in bricks.
  static constexpr int kMaxLeapRadius = 8;
  /// Every brick empty: a grid of bricks covering `cell` sample spacings each, per axis.
  void reset(std::array<int, 3> grid, std::array<int, 3> cell);
  /// Brick b drawn flat in c (opacity per voxel of depth; below kMinFlatAlpha it stays empty).
  void set_flat(int b, const tsp::Rgba& c);
  /// Brick b sampled from slot (a leaf's, or a level brick's covering b: slot.scale < 1); with
  /// clipped, the clip surface may cross it and the ray caster tests its samples; a level
  /// brick's tf_row > 0 (< tsp::kLevelTfRows) samples that row of the levels' TF table
  /// (tsp/metric/level_tf.h) instead of the TF.
  void set_textured(int b, const BrickSlot& slot, bool clipped = false, int tf_row = 0);
  /// Added to a textured page's code when its samples are tested against the clip solid.
  static constexpr int kClipFlag = ray::kClipFlag;
  /// A textured page's code carries its TF row times this.
  static constexpr int kLevelRowUnit = ray::kLevelRowUnit;
  /// After the last set_*: gives every empty brick the radius of the cube of empty bricks centred
  /// on it (Chebyshev distance to the nearest non-empty brick − 1, at most kMaxLeapRadius), which
  /// the ray caster leaps over.
  void finish();
  /// Bricks per axis.
  const std::array<int, 3>& grid() const { return grid_; }
  /// Sample spacings one brick covers per axis.
  const std::array<int, 3>& cell() const { return cell_; }
  /// Per brick, four floats: textured (atlas offset xyz, 1 + LOD code), flat (rgb, ln(1 − α) < 0) or empty
  /// (leap radius, 0, 0, 0).
  const std::vector<float>& texels() const { return texels_; }
  /// The atlas the textured bricks read (0: none).
  const BrickSlot& atlas() const { return atlas_; }
  /// Marks (after reset) that every full-resolution page reads BrickTextures' dense region, so
  /// neighbouring pages' texels sit side by side (the CPU caster walks runs of them as one).
  void set_runs(bool on) { runs_ = on; }
  /// True when set_runs(true) was called since the last reset.
  bool runs() const { return runs_; }

 private:
  std::array<int, 3> grid_{}, cell_{};
  std::vector<float> texels_;
  BrickSlot atlas_;
  bool runs_ = false;
};

}  // namespace tspgl

// What a frame is drawn with (besides camera and metric) and what it reports: shared by the TSP
// renderer, the non-TSP baseline, the render and bench jobs and the player.
#pragma once
#include <array>
#include <cstdint>
#include <string>

#include "tsp/frame/frame_plan.h"
#include "tsp/tree/traversal.h"

namespace tspgl {

/// Slice spacing in voxels (half a voxel: Nyquist, spec §7).
inline constexpr double kDefaultSliceSpacing = 0.5;
/// Default texture budget of the TSP renderer's cache.
inline constexpr std::int64_t kDefaultTextureBudget = std::int64_t(512) << 20;
/// Default RAM budget for bricks read from the .tsp file.
inline constexpr std::int64_t kDefaultBrickBudget = std::int64_t(1024) << 20;
/// Slice spacings accepted, in voxels: below 1/64 a frame costs thousands of slices per brick
/// for no visible gain; above 64 a slice skips whole bricks.
inline constexpr double kMinSliceSpacing = 1.0 / 64, kMaxSliceSpacing = 64;
/// Largest texture, brick or upload budget accepted (1 TiB).
inline constexpr std::int64_t kMaxBudgetBytes = std::int64_t(1) << 40;

/// How a renderer draws textured boxes (bricks, or the baseline's whole volume).
enum class Compositing {
  slices,  ///< view-aligned slice polygons, one blended fragment per slice (paper §4.2)
  boxes,   ///< each brick's box ray cast on its own, one fragment per pixel per brick
  rays,    ///< the whole volume ray cast in one pass over the brick grid, same slice planes
};

/// "slices", "boxes" or "rays".
const char* to_string(Compositing c);
/// Parses "slices", "boxes" or "rays"; throws tsp::UsageError naming `option` and the text.
Compositing parse_compositing(const std::string& text, const std::string& option);

/// What a frame is drawn with, besides the camera and the metric.
struct RenderSettings {
  tsp::Tolerances tol;                       ///< spatial and temporal tolerances
  double spacing = kDefaultSliceSpacing;     ///< slice spacing in voxels (> 0)
  std::array<float, 3> background{0, 0, 0};  ///< opaque background colour
  /// Texture bytes one frame may upload (0: no limit). At least one texture is uploaded per
  /// frame; the bricks over the budget are drawn flat in their node's mean colour and uploaded
  /// by later frames (FrameReport::deferred_textures > 0 until the frame is complete).
  std::int64_t upload_budget = 0;
  Compositing compositing = Compositing::rays;  ///< how textured boxes are drawn
  /// Coherent (flat) nodes drawn as one box composited exactly over each ray's depth through it
  /// (true), or as flat slices every `spacing` (false: the paper's rule).
  bool exact_flat = true;
  /// Textured samples read a pre-integrated TF table over each pair of neighbouring samples
  /// (tsp::preintegrate) instead of the point lookup.
  bool preintegrated = false;
  /// Keep the last frame's pixels whose rays meet only bricks drawn as before (same view, TF and
  /// knobs), drawing only the rectangles of the bricks that changed (image_reuse.h). Exact.
  bool reuse_image = true;
  /// What textures a span longer than one step (its middle step by default: docs/rendering.md).
  tsp::SpanStep span_step = tsp::SpanStep::middle;
  /// Render-target size as a share of the window's per axis, in [kMinRenderScale, 1]: below 1
  /// the frame is drawn smaller and magnified (the LOD controller's last resort when even the
  /// coarsest cut misses the target). Partial-image reuse is off below 1.
  double render_scale = 1;
  /// Where the frame goes in the context's default framebuffer: the lower-left corner (GL window
  /// coordinates, y up); the frame's size is the camera's. The player docks its panels beside it.
  std::array<int, 2> viewport_origin{0, 0};
  /// Rays compositing: a frame that textures every leaf brick at full resolution is ray cast
  /// through one whole-volume texture (render/dense_volume.h) instead of walking the brick grid
  /// — the same samples, fewer diverging loops. False: always the brick grid.
  bool dense = true;
  /// A coherent node holding a transparent child is drawn as its children (tsp::traverse with
  /// the metric's transparency), so what zero tolerance skips is never drawn; false: the
  /// paper's rule (the node drawn whole).
  bool skip_transparent = true;
  /// Adaptive sampling (rays compositing without probes; tsp/frame/sample_steps.h): each leaf
  /// brick textured at full resolution is sampled every m·spacing, m the largest of
  /// tsp::kStepMultipliers whose step changes the premultiplied TF colour by at most this much
  /// (0: every brick every spacing). Excludes pre-integration.
  double sampling_tol = 0;
};

/// Smallest RenderSettings::render_scale.
inline constexpr double kMinRenderScale = 0.25;

/// Throws tsp::UsageError naming the setting, its value and the accepted range unless spacing is
/// in [kMinSliceSpacing, kMaxSliceSpacing], both tolerances are finite and ≥ 0 and the upload
/// budget is in [0, kMaxBudgetBytes].
void validate(const RenderSettings& s);

/// Throws tsp::UsageError unless bytes is in [1, kMaxBudgetBytes]; `what` names the option.
void validate_budget(std::int64_t bytes, const std::string& what);

/// Timings and counts of one frame (the frames.json record, less pass).
struct FrameReport {
  int step = 0;
  /// The steps the drawn nodes stand for (the union of their time spans): wider than [step,
  /// step] when a temporal tolerance merged steps.
  int spans_lo = 0, spans_hi = 0;
  /// The steps whose bricks textured them (every step of a span textured by its mean).
  int shown_lo = 0, shown_hi = 0;
  /// Some texture holds a span's mean (--span-step mean) rather than one step.
  bool shows_mean = false;
  double ms = 0;            ///< whole frame, glFinish included
  double traversal_ms = 0;  ///< traversal and frame plan
  double slicing_ms = 0;    ///< slice polygons and their vertex buffer
  double upload_ms = 0;     ///< brick reads and texture uploads
  double draw_ms = 0;       ///< draw calls and glFinish
  /// Adaptive sampling: the mean step multiplier over the frame's full-resolution textured
  /// bricks (1: every spacing).
  double step_multiplier = 1;
  std::array<double, tsp::kDrawClassCount> class_percent{};  ///< NR, UP, RT, NT, clipped by voxels
  std::int64_t bytes_uploaded = 0;
  std::int64_t textures_resident = 0;
  std::int64_t texture_bytes = 0;
  std::int64_t polygons = 0;           ///< slice polygons drawn
  std::int64_t boxes = 0;              ///< boxes drawn whole (ray cast or exact flat)
  std::int64_t fragments = 0;          ///< fragments drawn, not discarded (GL_SAMPLES_PASSED)
  double redrawn_percent = 100;        ///< share of the image drawn again (partial-image reuse)
  bool dense = false;  ///< ray cast as one whole-volume texture (DenseVolume), not the brick grid
  std::int64_t deferred_textures = 0;  ///< textures left for later frames (upload_budget)
  /// True when every texture the frame needs was drawn (nothing deferred).
  bool complete() const { return deferred_textures == 0; }
};

}  // namespace tspgl

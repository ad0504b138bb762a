// src/render: drawing frames with GL; may include tsp/, gl/.
// What a frame is drawn with besides the camera and the metric: one value type shared by the TSP
// renderer, the baseline, the render and bench jobs and the player. Its user-facing knobs — their
// names, ranges, units, help and groups — are listed once, in settings_table.h.
#pragma once
#include <array>
#include <cstdint>
#include <string>

#include "tsp/frame/frame_plan.h"
#include "tsp/frame/refine.h"
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

/// Lighting (RenderSettings::shade): Blinn–Phong coefficients, vtkVolumeProperty's defaults
/// (Ambient 0.1, Diffuse 0.7, Specular 0.2, SpecularPower 10).
inline constexpr double kAmbient = 0.1, kDiffuse = 0.7, kSpecular = 0.2, kSpecularPower = 10;

/// How a renderer draws textured boxes (bricks, or the baseline's whole volume).
enum class Compositing {
  slices,  ///< view-aligned slice polygons, one blended fragment per slice (paper §4.2)
  boxes,   ///< each brick's box ray cast on its own, one fragment per pixel per brick
  rays,    ///< the whole volume ray cast in one pass over the brick grid, same slice planes
};

/// Who casts a frame's rays (rays compositing).
enum class Backend {
  automatic,  ///< cpu where the GL renderer is software (llvmpipe, softpipe, swrast), else gl
  gl,         ///< the GLSL caster (shaders/volume_ray.frag)
  cpu,        ///< the native caster (render/cpu_caster.h)
};

/// "auto", "gl" or "cpu".
const char* to_string(Backend b);

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
  /// Who casts the rays; a frame the CPU caster cannot draw is drawn by GL
  /// (FrameReport::backend, backend_note).
  Backend backend = Backend::automatic;
  /// Coherent (flat) nodes drawn as one box composited exactly over each ray's depth through it
  /// (true), or as flat slices every `spacing` (false: the paper's rule).
  bool exact_flat = true;
  /// Textured samples read a pre-integrated TF table over each pair of neighbouring samples
  /// (tsp::preintegrate) instead of the point lookup.
  bool preintegrated = false;
  /// Textured samples lit by a headlight (Blinn–Phong, kAmbient … kSpecularPower; the normal
  /// from central differences of the scalar; across a brick face from the neighbour brick when
  /// it is a level-0 texture, else one-sided). Uniform data and flat nodes stay unlit. On by
  /// default (issue 29): docs/rendering.md says where the brick grid's picture differs from
  /// the whole-volume paths' (dense, baseline).
  bool shade = true;
  /// The one-pass caster classifies an LOD level brick with the TF averaged over the spread of
  /// the voxels each of its samples stands for (the level's residual σ: tsp/metric/level_tf.h),
  /// so thin TF bands survive at coarse levels; false: the TF itself (LaMar's opacity
  /// correction alone). Slices and boxes compositing always use the TF itself.
  bool level_tf = true;
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
  /// Refinement (rays compositing without probes, neither adaptive sampling nor
  /// pre-integration; tsp/frame/refine.h): the TF is cut into pieces that stay within this of a
  /// straight line (premultiplied colour and opacity at the spacing, tsp::tf_pieces), and a
  /// segment whose middle falls in another piece than a neighbouring middle is sampled
  /// tsp::kRefineSamples times finer, so thin bands and one-voxel jumps are drawn where they lie
  /// (0: off).
  double refine_tol = tsp::kDefaultRefineTol;
  /// Rays compositing: the mesh's boundary drawn opaque under the volume from TetSplat's splat
  /// hierarchy (render/surface_splats.h), where the caller gives the compositor one.
  bool surface = false;
  /// The boundary's minimum splat size in pixels, in [0, kMaxSurfacePx] (0: every leaf).
  double surface_px = 1;
  /// Every field equal.
  bool operator==(const RenderSettings&) const = default;
};

/// Largest RenderSettings::surface_px (a splat as wide as a large window).
inline constexpr double kMaxSurfacePx = 4096;

/// Smallest RenderSettings::render_scale.
inline constexpr double kMinRenderScale = 0.25;

/// Throws tsp::UsageError unless every knob of s lies in its settings-table row's range (the
/// row's message: "--spacing '100': expected a number in [0.015625, 64] (voxels)", check_setting
/// in settings_table.h) and its sampling knobs hold together (sampling_conflict).
void validate(const RenderSettings& s);

/// How a frame's full-resolution rays sample (rays compositing without probes): the knobs'
/// one reading, with the rule that the three modes exclude each other.
enum class SamplingMode {
  segments,       ///< one sample per segment at its middle (refine_tol 0)
  preintegrated,  ///< the pre-integrated table between each segment's two ends
  adaptive,       ///< segments of m spacings (sampling_tol > 0)
  refined,        ///< segments refined where the TF bends (refine_tol > 0, the default)
};
/// The mode s asks for: adaptive when sampling_tol > 0, else pre-integrated, else refined when
/// refine_tol > 0, else plain segments — refinement yields to either other mode; adaptive
/// sampling and pre-integration together are refused by validate() (sampling_conflict). Never
/// throws.
SamplingMode resolve_sampling(const RenderSettings& s);
/// Why s's sampling knobs cannot hold together (adaptive sampling with pre-integration), or ""
/// when they can: the one message for that rule. Never throws but bad_alloc.
std::string sampling_conflict(const RenderSettings& s);
/// Settles a conflict the way a user who just changed one knob means it: the knob named
/// `changed` ("preintegrated" or "sampling-tol") wins, the other is turned off. Returns what was
/// turned off, for the status line ("" when nothing was). Never throws but bad_alloc.
std::string settle_sampling(RenderSettings& s, const std::string& changed);

/// Throws tsp::UsageError unless bytes is in [1, kMaxBudgetBytes]; `what` names the option.
void validate_budget(std::int64_t bytes, const std::string& what);

}  // namespace tspgl

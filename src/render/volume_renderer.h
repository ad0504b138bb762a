// src/render: drawing frames with GL (TSP renderer, baseline, compositing); may include tsp/, gl/.
// The TSP renderer: one time step of a TSP tree drawn with OpenGL — traversal → frame plan →
// flat or textured slice polygons, back to front, composited by a SliceCompositor. The non-TSP
// baseline is baseline_renderer.h.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "gl/context.h"
#include "render/brick_textures.h"
#include "render/dense_volume.h"
#include "render/frame_report.h"
#include "render/image_reuse.h"
#include "render/slice_compositor.h"
#include "tsp/frame/camera.h"
#include "tsp/frame/frame_plan.h"
#include "tsp/frame/sample_steps.h"
#include "tsp/frame/texture_cache.h"
#include "tsp/metric/frame_metric.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/store/brick_cache.h"
#include "tsp/store/brick_store.h"

namespace tspgl {

/// Part of a picture drawn by one frame (the player's progressive refinement, docs/player.md
/// "No popping"): only rects are drawn; the rest of the picture keeps the last frame's pixels
/// (magnified to full size when the last frame was drawn smaller).
struct PartialFrame {
  std::vector<PixelRect> rects;  ///< render-target pixels, origin bottom left
  bool first = false;            ///< the first part of a picture
  bool completes = false;        ///< the part that completes it (partial-image reuse resumes)
};

/// Renders steps of one brick store (a .tsp file or an in-memory store) into the current
/// framebuffer of a GL context. Use from the context's thread; brick_cache() alone may be used
/// from a prefetch thread as well.
class VolumeRenderer {
 public:
  /// Sets up programs and buffers in ctx (which must be current and outlive the renderer);
  /// bricks must outlive it too and have a thread-safe read_brick. With compositor (made in
  /// ctx), its programs are shared instead of compiled again: one renderer per field of a file
  /// (the player's field switch), drawing one at a time. Throws tsp::GlError, tsp::IoError
  /// (shader files).
  VolumeRenderer(GlContext& ctx, const tsp::BrickStore& bricks, tsp::CachePolicy cache,
                 std::int64_t texture_budget = kDefaultTextureBudget,
                 std::int64_t brick_budget = kDefaultBrickBudget,
                 std::shared_ptr<SliceCompositor> compositor = nullptr);
  /// The tree it draws.
  const tsp::TspTree& tree() const { return tree_; }
  /// The compositor it draws with (to share with another renderer in the same context).
  const std::shared_ptr<SliceCompositor>& compositor() const { return compositor_; }
  ~VolumeRenderer();
  VolumeRenderer(const VolumeRenderer&) = delete;
  VolumeRenderer& operator=(const VolumeRenderer&) = delete;

  /// Uses tf from the next frame on (1D lookup texture; never invalidates brick textures).
  void set_transfer_function(const tsp::TransferFunction& tf);
  /// With off, the CPU caster reads every brick from its atlas slot and walks brick by brick
  /// instead of runs of the dense region (BrickTextures::place_dense): the layouts' comparison
  /// in tests and benchmarks. On by default.
  void set_dense_host(bool on) { dense_host_ = on; }
  /// Clips the next frames to clip (tsp/clip; an empty region clips nothing): nodes it removes
  /// are neither drawn nor uploaded (class clipped), nodes across its surface are drawn
  /// textured and clipped per sample by the one-pass ray caster — frames with probes are ray
  /// cast whatever the compositing setting — and with surface the clip surface shows the data
  /// in surface's colours, opaque, shaded by its normal. Throws tsp::GlError.
  void set_clip(const tsp::ClipRegion& clip, const std::optional<tsp::TransferFunction>& surface);
  /// The clip region in use.
  const tsp::ClipRegion& clip() const { return clip_; }
  /// Per octree node, where it lies with respect to the clip region (empty: none), for the LOD
  /// cut.
  tsp::ClipSides clip_sides() const { return clip_sides_; }
  /// Draws step with the TSP tree: metric gives every node's errors, mean colour and
  /// transparency (a live metric evaluates only what step's traversal can visit, spec §4).
  /// With stops (an LOD cut, tsp/lod), the descent ends at the marked nodes, which draw their
  /// level bricks. Throws tsp::Error on brick read failures, tsp::GlError on GL failures.
  /// With part, only part's rectangles are drawn (at full size, whatever settings'
  /// render_scale was before); the report's partial_stale says when earlier parts of the picture
  /// were drawn differently.
  FrameReport render(int step, const tsp::Camera& camera, const RenderSettings& settings,
                     tsp::FrameMetric& metric, tsp::LodStops stops = {},
                     const PartialFrame* part = nullptr);
  /// The textures step's frame would upload under metric: those of textured nodes not
  /// resident, in the traversal's order (repeats possible).
  std::vector<tsp::TextureKey> textures_to_upload(int step, const tsp::Camera& camera,
                                                  const RenderSettings& settings,
                                                  tsp::FrameMetric& metric,
                                                  tsp::LodStops stops = {}) const;
  /// The brick reads (brick, step) those textures need — one per texture, every step of the
  /// span for a span's mean. For background prefetching.
  std::vector<tsp::BrickKey> bricks_to_upload(int step, const tsp::Camera& camera,
                                              const RenderSettings& settings,
                                              tsp::FrameMetric& metric,
                                              tsp::LodStops stops = {}) const;
  /// After a tolerance (or metric) change: deletes the textures no frame can draw any more under
  /// metric and tol (one traversal per step; skip_transparent: RenderSettings::skip_transparent
  /// of the frames to come) and returns how many. TF edits need no call. Throws what metric
  /// throws.
  int drop_unreachable(tsp::FrameMetric& metric, const tsp::Tolerances& tol, bool skip_transparent,
                       tsp::SpanStep span_step = tsp::SpanStep::middle, tsp::LodStops stops = {});
  /// Deletes every cached texture.
  void clear_textures();

  /// The RAM brick cache uploads read through (thread-safe; for a prefetch thread).
  tsp::BrickCache& brick_cache() { return bricks_; }
  /// The texture cache policy (for tolerance changes and statistics).
  tsp::TextureCache& texture_cache() { return cache_; }
  /// Number of GL brick textures alive.
  int texture_count() const { return textures_.size(); }
  /// The GL brick textures and what is kept with each (adaptive sampling's variations).
  const BrickTextures& textures() const { return textures_; }

 private:
  const tsp::TspTree& tree_;
  tsp::TextureCache cache_;
  tsp::BrickCache bricks_;
  std::shared_ptr<SliceCompositor> compositor_;
  BrickTextures textures_;
  DenseVolume dense_;  // rays compositing of frames that texture every leaf brick
  std::vector<tsp::TextureKey> dense_keys_;
  tsp::PolygonSoup soup_;
  std::vector<DrawItem> items_;  // slices and boxes compositing
  // What the last complete frame was drawn with, for partial-image reuse.
  struct ReuseKey {
    glm::dmat4 view_projection{1.0};
    int width = 0, height = 0;
    double spacing = 0;
    Compositing compositing = Compositing::rays;
    bool exact_flat = true, preintegrated = false, shade = false, skip_transparent = true;
    bool level_tf = false;
    std::array<float, 3> background{};
    std::uint64_t tf_serial = 0;
    std::uint64_t clip_serial = 0;
    double render_scale = 1;
    Backend backend = Backend::automatic;
    double sampling_tol = 0;
    double refine_tol = 0;
    bool surface = false;
    bool operator==(const ReuseKey&) const = default;
  };
  struct Previous {
    ReuseKey key;
    BrickIdentities ids;
  };
  std::optional<Previous> previous_;
  // The picture partial frames are building: what its parts were drawn with, and whether
  // every part since the first was drawn with the same.
  std::optional<Previous> partial_;
  bool partial_same_ = false;
  std::uint64_t tf_serial_ = 0;  // set_transfer_function calls
  std::vector<std::uint64_t> histogram_;  // the store's value histogram (the level TF's prior)
  tsp::ClipRegion clip_;
  bool clip_surface_ = false;
  std::vector<tsp::ClipSide> clip_sides_;  // per octree node, empty: no clip
  std::uint64_t clip_serial_ = 0;         // set_clip calls that changed it
  ReuseKey reuse_key(const tsp::Camera& camera, const RenderSettings& s) const;
  // The traversal of step under s with errors (metric's for step), the clip sides in use and,
  // with s.skip_transparent, metric's transparency; stops: the LOD cut (empty: none).
  tsp::TraversalQuery traversal(int step, const RenderSettings& s, tsp::FrameMetric& metric,
                                const tsp::NodeErrors& errors, const tsp::ViewOrder& order,
                                tsp::LodStops stops) const;
  BrickPages pages_;             // rays compositing
  struct LeafShading {
    tsp::Shading shading = tsp::Shading::none;
    int tsp_id = -1;
  };
  std::vector<LeafShading> leaf_shading_;  // per leaf brick, full resolution (LOD frames)
  std::vector<std::int64_t> level_pages_;  // leaf_shading_ as identity tags (image reuse)
  // One frame between the stages of render(): plan → upload → compose → draw → report.
  struct Frame {
    RenderSettings settings;  // as requested; ray cast where probes clip
    tsp::FramePlan plan;
    ReuseKey key;                  // what it is drawn with (partial-image reuse)
    BrickIdentities ids;           // what each brick shows
    bool reuse = false;            // only rects are drawn again
    const PartialFrame* part = nullptr;  // a partial frame: its rects only
    std::vector<PixelRect> rects;  // the screen rectangles that changed
  };
  // Traversal and frame plan (the cache decides), the leaves' shading under level bricks and
  // the reuse decision.
  Frame plan(int step, const tsp::Camera& camera, const RenderSettings& requested,
             tsp::FrameMetric& metric, tsp::LodStops stops, const PartialFrame* part = nullptr);
  // Ray casting level bricks: every leaf page's full-resolution shading under full, the
  // traversal without the LOD cut (leaf_shading_, level_pages_); clears level_pages_ otherwise.
  void shade_leaves(const tsp::TraversalQuery& full, const Frame& f, tsp::FrameMetric& metric);
  // Compares f with the last complete frame (f.key, f.ids, f.reuse, f.rects); forgets it.
  void decide_reuse(Frame& f, const tsp::Camera& camera, tsp::FrameMetric& metric);
  // Deletes and uploads f's textures; a dense frame's whole-volume texture too (r.dense).
  void upload(const Frame& f, FrameReport& r);
  // What the rays cross: the bounds of the drawn nodes (within the clip solid's, without a
  // surface); empty when nothing is drawn.
  tsp::Aabb drawn_bounds(const tsp::FramePlan& plan) const;
  // The brick pages (rays) or the draw list (slices, boxes), and adaptive sampling's step map.
  void compose(const Frame& f, const tsp::Camera& camera, tsp::FrameMetric& metric, FrameReport& r);
  // Draws (only f.rects when reusing), deletes the plan's release_after, ends the frame and
  // keeps it for reuse.
  void draw(Frame& f, const tsp::Camera& camera, FrameReport& r);
  // The plan's class shares, texture counts and the steps the picture stands for and shows.
  void report(const tsp::FramePlan& plan, FrameReport& r) const;
  void fill_items(const tsp::FramePlan& plan, tsp::FrameMetric& metric, const tsp::Camera& camera,
                  const RenderSettings& settings);
  void fill_pages(const tsp::FramePlan& plan, tsp::FrameMetric& metric, bool level_tf);
  // True when the clip surface may cross leaf brick `brick` (its node is not wholly kept).
  bool leaf_clipped(int brick) const;
  // True when plan textures every leaf brick at full resolution (fills dense_keys_).
  bool dense_frame(const tsp::FramePlan& plan);
  bool dense_host_ = true;  // set_dense_host
  // Adaptive sampling: gives the compositor the step row of every step-grid cell from plan's
  // level-0 textures (tsp::step_rows) and returns the mean multiplier over the cells they reach.
  double set_step_map(const tsp::FramePlan& plan, const RenderSettings& settings);
  tsp::TransferFunction tf_;  // the TF in use (adaptive sampling measures under it)
  std::optional<tsp::SampleVariation> variation_;  // under tf_ (reset by set_transfer_function)
  std::vector<float> cell_variation_;    // per step-grid cell, this frame
  std::vector<std::uint8_t> cell_drawn_;  // per step-grid cell: a textured brick reaches it
};

}  // namespace tspgl

// Draws one time step of a .tsp file with OpenGL: the TSP renderer (traversal → frame plan →
// flat or textured slice polygons, back to front) and the non-TSP baseline (the whole volume
// uploaded as one texture each step and sliced as one box).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

#include "gl/context.h"
#include "gl/shader.h"
#include "tsp/frame/camera.h"
#include "tsp/frame/frame_plan.h"
#include "tsp/frame/slicing.h"
#include "tsp/frame/texture_cache.h"
#include "tsp/metric/lazy_errors.h"
#include "tsp/metric/metric.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/store/brick_cache.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {

/// Slice spacing in voxels (half a voxel: Nyquist, spec §7).
inline constexpr double kDefaultSliceSpacing = 0.5;
/// Default texture budget of the TSP renderer's cache.
inline constexpr std::int64_t kDefaultTextureBudget = std::int64_t(512) << 20;
/// Default RAM budget for bricks read from the .tsp file.
inline constexpr std::int64_t kDefaultBrickBudget = std::int64_t(1024) << 20;

/// What a frame is drawn with, besides the camera and the metric.
struct RenderSettings {
  tsp::Tolerances tol;                       ///< spatial and temporal tolerances
  double spacing = kDefaultSliceSpacing;     ///< slice spacing in voxels (> 0)
  std::array<float, 3> background{0, 0, 0};  ///< opaque background colour
  /// Texture bytes one frame may upload (0: no limit). At least one texture is uploaded per
  /// frame; the bricks over the budget are drawn flat in their node's mean colour and uploaded
  /// by later frames (FrameReport::deferred_textures > 0 until the frame is complete).
  std::int64_t upload_budget = 0;
};

/// Timings and counts of one frame (the frames.json record, less pass).
struct FrameReport {
  int step = 0;
  double ms = 0;            ///< whole frame, glFinish included
  double traversal_ms = 0;  ///< traversal and frame plan
  double slicing_ms = 0;    ///< slice polygons and their vertex buffer
  double upload_ms = 0;     ///< brick reads and texture uploads
  double draw_ms = 0;       ///< draw calls and glFinish
  std::array<double, tsp::kDrawClassCount> class_percent{};  ///< NR, UP, RT, NT by voxels
  std::int64_t bytes_uploaded = 0;
  std::int64_t textures_resident = 0;
  std::int64_t texture_bytes = 0;
  std::int64_t polygons = 0;  ///< slice polygons drawn
  std::int64_t deferred_textures = 0;  ///< textures left for later frames (upload_budget)
  /// True when every texture the frame needs was drawn (nothing deferred).
  bool complete() const { return deferred_textures == 0; }
};

/// Renders steps of one .tsp file into the current framebuffer of a GL context.
class VolumeRenderer {
 public:
  /// Sets up programs and buffers in ctx (which must be current and outlive the renderer).
  /// Throws tsp::GlError, tsp::IoError (shader files).
  VolumeRenderer(GlContext& ctx, const tsp::TspFile& file, tsp::CachePolicy cache,
                 std::int64_t texture_budget = kDefaultTextureBudget,
                 std::int64_t brick_budget = kDefaultBrickBudget);
  ~VolumeRenderer();
  VolumeRenderer(const VolumeRenderer&) = delete;
  VolumeRenderer& operator=(const VolumeRenderer&) = delete;

  /// Uses tf from the next frame on (1D lookup texture; never invalidates brick textures).
  void set_transfer_function(const tsp::TransferFunction& tf);
  /// Draws step with the TSP tree: metric gives every node's errors, mean colour and
  /// transparency. Throws tsp::Error on brick read failures, tsp::GlError on GL failures.
  FrameReport render(int step, const tsp::Camera& camera, const RenderSettings& settings,
                     const tsp::MetricResult& metric);
  /// Same, with live errors: only the nodes step's traversal can visit are (re)evaluated, so a
  /// TF edit costs what the next frame needs (spec §4). Throws like render.
  FrameReport render(int step, const tsp::Camera& camera, const RenderSettings& settings,
                     tsp::LazyErrors& metric);
  /// The bricks (brick, span start) step's frame would read and upload under metric: leaf
  /// bricks of textured nodes whose texture is not resident. For background prefetching.
  std::vector<tsp::BrickKey> bricks_to_upload(int step, const tsp::Camera& camera,
                                              const RenderSettings& settings,
                                              tsp::LazyErrors& metric) const;
  /// Same with a whole-tree metric.
  std::vector<tsp::BrickKey> bricks_to_upload(int step, const tsp::Camera& camera,
                                              const RenderSettings& settings,
                                              const tsp::MetricResult& metric) const;
  /// The RAM brick cache uploads read through (thread-safe; for a prefetch thread).
  tsp::BrickCache& brick_cache() { return bricks_; }
  /// Draws step without the tree: the whole volume uploaded as one texture and sliced as one
  /// box. Class shares report everything as new texture. Throws like render.
  FrameReport render_baseline(int step, const tsp::Camera& camera, const RenderSettings& settings);
  /// The texture cache policy (for tolerance changes and statistics).
  tsp::TextureCache& texture_cache() { return cache_; }
  /// Deletes every cached texture.
  void clear_textures();
  /// After a tolerance (or metric) change: deletes the textures no frame can draw any more under
  /// metric and tol (one traversal per step) and returns how many. TF edits need no call.
  int drop_unreachable(const tsp::MetricResult& metric, const tsp::Tolerances& tol);
  /// Same with live errors (evaluates every node once for the current TF).
  int drop_unreachable(tsp::LazyErrors& metric, const tsp::Tolerances& tol);
  /// Number of GL brick textures alive.
  int texture_count() const { return int(textures_.size()); }

 private:
  struct DrawItem {
    int first_polygon = 0, polygon_count = 0;
    int texture = -1;  ///< index into the plan's textures, −1 for a flat item
    std::array<float, 4> colour{};
  };
  /// Mean (unpremultiplied) colour of a TSP node under the frame's metric.
  using ColourFn = std::function<tsp::Rgba(int tsp_id)>;
  FrameReport render_tree(int step, const tsp::Camera& camera, const RenderSettings& settings,
                          const tsp::NodeErrors& errors, const tsp::NodeInfoFn& info,
                          const ColourFn& colour);
  std::vector<tsp::BrickKey> bricks_needed(int step, const tsp::Camera& camera,
                                           const RenderSettings& settings,
                                           const tsp::NodeErrors& errors,
                                           const tsp::NodeInfoFn& info) const;
  void begin_frame(const tsp::Camera& camera, const RenderSettings& settings);
  void end_frame();
  void upload_tf(double spacing);
  void ensure_target();
  void upload_vertices();
  void draw_items(const std::vector<DrawItem>& items, const std::vector<GLuint>& textures,
                  const std::vector<tsp::Box>& sample_boxes);
  GLuint upload_brick(int brick, int step);
  GLuint create_scalar_texture(int w, int h, int d, const std::uint16_t* data);
  void delete_texture(const tsp::TextureKey& key);

  GlContext& ctx_;
  const GlApi& gl_;
  const tsp::TspFile& file_;
  tsp::TextureCache cache_;
  tsp::BrickCache bricks_;
  Program textured_, flat_;
  GLuint vao_ = 0, vbo_ = 0, tf_texture_ = 0, baseline_texture_ = 0;
  GLuint fbo_ = 0, fbo_colour_ = 0;  ///< 16-bit render target: 8-bit blending of thin slices drifts
  int fbo_width_ = 0, fbo_height_ = 0;
  double tf_scale_ = 1, tf_offset_ = 0;  ///< normalised scalar → TF texture coordinate
  std::vector<tsp::Rgba> tf_entries_;      ///< the TF as given (uncorrected, not premultiplied)
  double tf_spacing_ = -1;                 ///< spacing the TF texture was corrected for
  std::unordered_map<tsp::TextureKey, GLuint, tsp::TextureKeyHash> textures_;
  tsp::PolygonSoup soup_;
  std::vector<float> vertices_;
  std::vector<GLint> firsts_;
  std::vector<GLsizei> counts_;
  std::vector<std::uint16_t> volume_;  ///< the baseline's whole step
};

}  // namespace tspgl

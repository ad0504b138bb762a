// The non-TSP baseline every benchmark compares with: each frame assembles the whole step from
// the bricks, uploads it as one texture and slices it as one box (no tree, no cache).
#pragma once
#include <cstdint>
#include <vector>

#include "gl/context.h"
#include "render/frame_report.h"
#include "render/host_volume.h"
#include "render/slice_compositor.h"
#include "tsp/frame/camera.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/store/brick_cache.h"
#include "tsp/store/brick_store.h"

namespace tspgl {

/// Renders whole steps of a brick store without the tree. Use from the context's thread.
class BaselineRenderer {
 public:
  /// Sets up programs and buffers in ctx (which must be current and outlive the renderer);
  /// bricks must outlive it. Throws tsp::GlError, tsp::IoError (shader files).
  BaselineRenderer(GlContext& ctx, const tsp::BrickStore& bricks,
                   std::int64_t brick_budget = kDefaultBrickBudget);
  ~BaselineRenderer();
  BaselineRenderer(const BaselineRenderer&) = delete;
  BaselineRenderer& operator=(const BaselineRenderer&) = delete;

  /// Uses tf from the next frame on.
  void set_transfer_function(const tsp::TransferFunction& tf);
  /// Draws step: the whole volume uploaded as one texture and drawn as one box (sliced, ray cast
  /// per box, or by the one-pass ray caster as a single brick: settings.compositing). Class shares
  /// report everything as new texture; tolerances and the upload budget are ignored. Throws
  /// tsp::Error on brick read failures, tsp::GlError on GL failures.
  FrameReport render(int step, const tsp::Camera& camera, const RenderSettings& settings);
  /// Its compositor (to set a surface under the volume).
  SliceCompositor& compositor() { return compositor_; }
  /// The RAM brick cache it reads through.
  const tsp::BrickCache& brick_cache() const { return bricks_; }

 private:
  const tsp::TspTree& tree_;
  tsp::BrickCache bricks_;
  SliceCompositor compositor_;
  GLuint texture_ = 0;
  HostVolume volume_;  ///< the whole step (GL uploads it; the CPU caster reads it)
  tsp::PolygonSoup soup_;
  BrickPages pages_;
};

}  // namespace tspgl

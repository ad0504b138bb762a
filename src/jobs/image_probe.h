// The pictures a knob search compares: the search's sample steps rendered into images on one
// offscreen context, by the TSP renderer or the non-TSP baseline under any knobs.
#pragma once
#include <memory>
#include <vector>

#include "gl/context.h"
#include "jobs/knob_search.h"
#include "render/baseline_renderer.h"
#include "render/volume_renderer.h"
#include "tsp/frame/camera.h"
#include "tsp/metric/metric.h"
#include "tsp/report/image.h"
#include "tsp/store/brick_store.h"

namespace tspgl {

/// A probe's pictures and its median frame time.
struct ProbeFrames {
  std::vector<tsp::Image> images;
  double median_ms = 0;
};

/// Renders fixed steps of one store under one TF (cache off: the pictures do not depend on the
/// cache, and nothing stale survives a tolerance change). Use from one thread.
class ImageProbe {
 public:
  /// An offscreen context of params' size. Throws tsp::GlError, tsp::UsageError (size).
  ImageProbe(const tsp::BrickStore& bricks, const tsp::TransferFunction& tf,
             const tsp::CameraParams& params, std::vector<int> steps);
  /// The steps under knobs k: the baseline when k.baseline, else the TSP renderer under metric
  /// (which must then be non-null). Throws like the renderers' render().
  ProbeFrames render(const Knobs& k, const tsp::MetricResult* metric);

 private:
  const tsp::BrickStore& bricks_;
  std::unique_ptr<GlContext> ctx_;
  VolumeRenderer renderer_;
  BaselineRenderer baseline_;
  tsp::Camera camera_;
  std::vector<int> steps_;
};

/// Mean over the pairs of images of their mean per-pixel ΔE (0 for none). Throws
/// tsp::UsageError when a pair's sizes differ.
double mean_delta_e(const std::vector<tsp::Image>& a, const std::vector<tsp::Image>& b);

}  // namespace tspgl

// The pictures a tolerance search compares: the search's sample steps rendered into images on
// one offscreen context, by the TSP renderer at a tolerance or by the non-TSP baseline.
#pragma once
#include <memory>
#include <vector>

#include "gl/context.h"
#include "render/baseline_renderer.h"
#include "render/volume_renderer.h"
#include "tsp/frame/camera.h"
#include "tsp/metric/metric.h"
#include "tsp/report/image.h"
#include "tsp/store/brick_store.h"

namespace tspgl {

/// Renders fixed steps of one store under one TF (cache off: the pictures do not depend on the
/// cache, and nothing stale survives a tolerance change). Use from one thread.
class ImageProbe {
 public:
  /// An offscreen context of params' size. Throws tsp::GlError, tsp::UsageError (size).
  ImageProbe(const tsp::BrickStore& bricks, const tsp::TransferFunction& tf,
             const tsp::CameraParams& params, std::vector<int> steps);
  /// The steps under metric at tolerance tol (spatial = temporal). Throws like render().
  std::vector<tsp::Image> render(const tsp::MetricResult& metric, double tol);
  /// The steps drawn by the non-TSP baseline. Throws like render().
  std::vector<tsp::Image> render_baseline();

 private:
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

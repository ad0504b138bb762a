// The pictures a knob search compares: the search's sample steps rendered into images on an
// offscreen canvas of the caller's context (gl/offscreen_canvas.h), by the TSP renderer or the
// non-TSP baseline under any knobs.
#pragma once
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "gl/context.h"
#include "gl/offscreen_canvas.h"
#include "jobs/knob_search.h"
#include "render/baseline_renderer.h"
#include "render/frame_driver.h"
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
/// cache, and nothing stale survives a tolerance change) in the caller's context, on an
/// offscreen canvas of the camera's size: the context's own framebuffer and its current state
/// are left as they were. Use from the context's thread.
class ImageProbe {
 public:
  /// Renderers and a canvas of params' size in ctx (current; it must outlive the probe). Throws
  /// tsp::GlError, tsp::UsageError (size).
  ImageProbe(GlContext& ctx, const tsp::BrickStore& bricks, const tsp::TransferFunction& tf,
             const tsp::CameraParams& params, std::vector<int> steps);
  /// The steps under knobs k: the baseline when k.baseline, else the TSP renderer under metric
  /// (which must then be non-null). Throws like the renderers' render().
  ProbeFrames render(const Knobs& k, const tsp::MetricResult* metric);
  /// The i-th of the steps under knobs k, and its frame time in ms (render() one step at a
  /// time, for a caller that spreads a calibration over its own frames). Throws like render().
  std::pair<tsp::Image, double> render_step(const Knobs& k, const tsp::MetricResult* metric,
                                            std::size_t i);
  /// The i-th of the steps drawn by the TSP renderer with settings s (their viewport origin
  /// ignored) at LOD level lod_level everywhere (0: full resolution) under nodes (e.g. a
  /// player's live metric), and its frame time in ms. Throws like render().
  std::pair<tsp::Image, double> render_step(const RenderSettings& s, int lod_level,
                                            tsp::FrameMetric& nodes, std::size_t i);
  /// Number of steps it renders.
  std::size_t steps() const { return steps_.size(); }
  /// Frees its GL objects in ctx (made current again first).
  ~ImageProbe();
  ImageProbe(const ImageProbe&) = delete;
  ImageProbe& operator=(const ImageProbe&) = delete;

 private:
  const tsp::BrickStore& bricks_;
  GlContext& ctx_;
  OffscreenCanvas canvas_;
  VolumeRenderer renderer_;
  BaselineRenderer baseline_;
  tsp::Camera camera_;
  std::vector<int> steps_;
  // The driver of the renderer, LOD level and metric last drawn: made once per configuration,
  // not per step.
  struct Drawing {
    bool baseline = false;
    int lod_level = 0;
    const tsp::MetricResult* metric = nullptr;  // the whole-tree metric nodes serve, if any
    tsp::FrameMetric* external = nullptr;       // else the caller's node metric
    std::unique_ptr<tsp::WholeTreeMetric> nodes;
    std::unique_ptr<FrameDriver> driver;
    tsp::FrameMetric* frame_metric() { return external ? external : nodes.get(); }
  };
  std::optional<Drawing> drawing_;
  Drawing& drawing_for(bool baseline, int lod_level, const tsp::MetricResult* metric,
                       tsp::FrameMetric* external);
  std::pair<tsp::Image, double> draw(Drawing& d, const RenderSettings& s, std::size_t i);
};

/// Mean over the pairs of images of their mean per-pixel ΔE (0 for none). Throws
/// tsp::UsageError when a pair's sizes differ.
double mean_delta_e(const std::vector<tsp::Image>& a, const std::vector<tsp::Image>& b);

}  // namespace tspgl

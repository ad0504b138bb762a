#include "jobs/image_probe.h"

#include <algorithm>
#include <cassert>
#include <optional>

#include "gl/gl_error.h"
#include "jobs/render_job.h"
#include "render/frame_driver.h"
#include "tsp/report/image_diff.h"

namespace tspgl {

ImageProbe::ImageProbe(GlContext& ctx, const tsp::BrickStore& bricks,
                       const tsp::TransferFunction& tf, const tsp::CameraParams& params,
                       std::vector<int> steps)
    : bricks_(bricks),
      ctx_(ctx),
      canvas_(ctx, params.width, params.height),
      renderer_(ctx, bricks, tsp::CachePolicy::off),
      baseline_(ctx, bricks),
      camera_(bricks.tree().octree().dims(), params),
      steps_(std::move(steps)) {
  renderer_.set_transfer_function(tf);
  baseline_.set_transfer_function(tf);
}

ImageProbe::~ImageProbe() {
  try {
    ctx_.make_current();
  } catch (const tsp::GlError&) {  // the members' GL deletes then go nowhere, as at exit
  }
}

ProbeFrames ImageProbe::render(const Knobs& k, const tsp::MetricResult* metric) {
  assert(k.baseline || metric);
  RenderSettings s;
  apply(k, s);
  std::unique_ptr<tsp::WholeTreeMetric> nodes;
  if (!k.baseline) nodes = std::make_unique<tsp::WholeTreeMetric>(*metric);
  // An LOD level everywhere (render --lod K, clamped to the tree's levels).
  LodSpec lod;
  if (!k.baseline && k.lod_level > 0) {
    lod.mode = LodMode::fixed;
    lod.level = k.lod_level;
  }
  FrameDriver driver = k.baseline ? FrameDriver(baseline_) : FrameDriver(renderer_, lod);
  ProbeFrames out;
  std::vector<double> ms;
  ctx_.make_current();  // the caller's context (a render job in between may have made its own)
  const CanvasScope scope(canvas_);
  for (int t : steps_) {
    FrameRequest r;
    r.step = t;
    r.camera = &camera_;
    r.settings = s;
    r.metric = nodes.get();
    ms.push_back(driver.draw(r).report.ms);
    out.images.push_back(ctx_.read_pixels());
  }
  out.median_ms = median(std::move(ms));
  return out;
}

double mean_delta_e(const std::vector<tsp::Image>& a, const std::vector<tsp::Image>& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += tsp::diff_images(a[i], b[i]).mean;
  return a.empty() ? 0 : sum / double(a.size());
}

}  // namespace tspgl

#include "jobs/image_probe.h"

#include <algorithm>
#include <cassert>
#include <optional>

#include "gl/gl_error.h"
#include "jobs/render_job.h"
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
    // Nothing of ours stays bound: a program deleted while current lives on until unbound, and
    // a window's UI back end that saved it as "current" would restore a name that is gone.
    ctx_.gl().UseProgram(0);
    ctx_.gl().BindVertexArray(0);
  } catch (const tsp::GlError&) {  // the members' GL deletes then go nowhere, as at exit
  }
}

std::pair<tsp::Image, double> ImageProbe::render_step(const Knobs& k,
                                                      const tsp::MetricResult* metric,
                                                      std::size_t i) {
  assert(k.baseline || metric);
  assert(i < steps_.size());
  Drawing& d = drawing_for(k, metric);
  ctx_.make_current();  // the caller's context (a render job in between may have made its own)
  const CanvasScope scope(canvas_);
  FrameRequest r;
  r.step = steps_[i];
  r.camera = &camera_;
  apply(k, r.settings);
  r.metric = d.nodes.get();
  const double ms = d.driver->draw(r).report.ms;
  return {ctx_.read_pixels(), ms};
}

ImageProbe::Drawing& ImageProbe::drawing_for(const Knobs& k, const tsp::MetricResult* metric) {
  if (drawing_ && drawing_->knobs == k && drawing_->metric == metric) return *drawing_;
  Drawing d;
  d.knobs = k;
  d.metric = metric;
  if (!k.baseline) d.nodes = std::make_unique<tsp::WholeTreeMetric>(*metric);
  // An LOD level everywhere (render --lod K, clamped to the tree's levels).
  LodSpec lod;
  if (!k.baseline && k.lod_level > 0) {
    lod.mode = LodMode::fixed;
    lod.level = k.lod_level;
  }
  d.driver = k.baseline ? std::make_unique<FrameDriver>(baseline_)
                        : std::make_unique<FrameDriver>(renderer_, lod);
  drawing_ = std::move(d);
  return *drawing_;
}

ProbeFrames ImageProbe::render(const Knobs& k, const tsp::MetricResult* metric) {
  ProbeFrames out;
  std::vector<double> ms;
  for (std::size_t i = 0; i < steps_.size(); ++i) {
    auto [image, frame_ms] = render_step(k, metric, i);
    out.images.push_back(std::move(image));
    ms.push_back(frame_ms);
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

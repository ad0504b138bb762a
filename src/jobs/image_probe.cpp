#include "jobs/image_probe.h"

#include <algorithm>
#include <cassert>
#include <optional>

#include "gl/gl_error.h"
#include "jobs/render_job.h"
#include "tsp/core/interrupt.h"
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
  RenderSettings s;
  apply(k, s);
  return draw(drawing_for(k.baseline, k.baseline ? 0 : k.lod_level, metric, nullptr), s, i);
}

std::pair<tsp::Image, double> ImageProbe::render_step(const RenderSettings& s, int lod_level,
                                                      tsp::FrameMetric& nodes, std::size_t i) {
  RenderSettings own = s;
  own.viewport_origin = {0, 0};
  return draw(drawing_for(false, lod_level, nullptr, &nodes), own, i);
}

std::pair<tsp::Image, double> ImageProbe::draw(Drawing& d, const RenderSettings& s, std::size_t i) {
  assert(i < steps_.size());
  // Every search and calibration draws through here: a SIGINT/SIGTERM stops them within a frame.
  tsp::throw_if_interrupted();
  ctx_.make_current();  // the caller's context (a render job in between may have made its own)
  const CanvasScope scope(canvas_);
  FrameRequest r;
  r.step = steps_[i];
  r.camera = &camera_;
  r.settings = s;
  r.metric = d.frame_metric();
  const double ms = d.driver->draw(r).report.ms;
  return {ctx_.read_pixels(), ms};
}

ImageProbe::Drawing& ImageProbe::drawing_for(bool baseline, int lod_level,
                                             const tsp::MetricResult* metric,
                                             tsp::FrameMetric* external) {
  if (drawing_ && drawing_->baseline == baseline && drawing_->lod_level == lod_level &&
      drawing_->metric == metric && drawing_->external == external)
    return *drawing_;
  Drawing d;
  d.baseline = baseline;
  d.lod_level = lod_level;
  d.metric = metric;
  d.external = external;
  if (!baseline && !external) d.nodes = std::make_unique<tsp::WholeTreeMetric>(*metric);
  // An LOD level everywhere (render --lod K, clamped to the tree's levels).
  LodSpec lod;
  if (!baseline && lod_level > 0) {
    lod.mode = LodMode::fixed;
    lod.level = lod_level;
  }
  d.driver = baseline ? std::make_unique<FrameDriver>(baseline_)
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

#include "jobs/image_probe.h"

#include "tsp/report/image_diff.h"

namespace tspgl {

ImageProbe::ImageProbe(const tsp::BrickStore& bricks, const tsp::TransferFunction& tf,
                       const tsp::CameraParams& params, std::vector<int> steps)
    : ctx_(create_offscreen_context(params.width, params.height)),
      renderer_(*ctx_, bricks, tsp::CachePolicy::off),
      baseline_(*ctx_, bricks),
      camera_(bricks.tree().octree().dims(), params),
      steps_(std::move(steps)) {
  renderer_.set_transfer_function(tf);
  baseline_.set_transfer_function(tf);
}

std::vector<tsp::Image> ImageProbe::render(const tsp::MetricResult& metric, double tol) {
  RenderSettings s;
  s.tol = {tol, tol};
  tsp::WholeTreeMetric nodes(metric);
  std::vector<tsp::Image> out;
  for (int t : steps_) {
    renderer_.render(t, camera_, s, nodes);
    out.push_back(ctx_->read_pixels());
  }
  return out;
}

std::vector<tsp::Image> ImageProbe::render_baseline() {
  std::vector<tsp::Image> out;
  for (int t : steps_) {
    baseline_.render(t, camera_, RenderSettings{});
    out.push_back(ctx_->read_pixels());
  }
  return out;
}

double mean_delta_e(const std::vector<tsp::Image>& a, const std::vector<tsp::Image>& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += tsp::diff_images(a[i], b[i]).mean;
  return a.empty() ? 0 : sum / double(a.size());
}

}  // namespace tspgl

#include "jobs/image_probe.h"

#include <algorithm>
#include <cassert>
#include <optional>

#include "jobs/render_job.h"
#include "tsp/lod/lod_cut.h"
#include "tsp/report/image_diff.h"

namespace tspgl {

ImageProbe::ImageProbe(const tsp::BrickStore& bricks, const tsp::TransferFunction& tf,
                       const tsp::CameraParams& params, std::vector<int> steps)
    : bricks_(bricks),
      ctx_(create_offscreen_context(params.width, params.height)),
      renderer_(*ctx_, bricks, tsp::CachePolicy::off),
      baseline_(*ctx_, bricks),
      camera_(bricks.tree().octree().dims(), params),
      steps_(std::move(steps)) {
  renderer_.set_transfer_function(tf);
  baseline_.set_transfer_function(tf);
}

ProbeFrames ImageProbe::render(const Knobs& k, const tsp::MetricResult* metric) {
  assert(k.baseline || metric);
  RenderSettings s;
  apply(k, s);
  std::unique_ptr<tsp::WholeTreeMetric> nodes;
  if (!k.baseline) nodes = std::make_unique<tsp::WholeTreeMetric>(*metric);
  // An LOD level everywhere (render --lod K, clamped to the tree's levels).
  std::optional<tsp::LodCut> cut;
  if (!k.baseline && k.lod_level > 0) {
    const tsp::Octree& o = bricks_.tree().octree();
    cut = tsp::LodCut::at_level(o, std::min(k.lod_level, o.max_lod_level()));
  }
  ProbeFrames out;
  std::vector<double> ms;
  for (int t : steps_) {
    const FrameReport r = k.baseline ? baseline_.render(t, camera_, s)
                                     : renderer_.render(t, camera_, s, *nodes,
                                                        cut ? cut->stops() : tsp::LodStops{});
    ms.push_back(r.ms);
    out.images.push_back(ctx_->read_pixels());
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

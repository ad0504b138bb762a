#include "support/function_scene.h"

#include "support/function_tsp.h"

namespace tsptest {

FunctionScene::FunctionScene(const std::string& name,
                             const std::function<float(int, int, int, int)>& f,
                             const tsp::TransferFunction& tf, tsp::Dims dims, int width,
                             int height)
    : file(tsp::TspFile::open(build_function_tsp(name, dims, f))),
      ctx(tspgl::create_offscreen_context(width, height)) {
  renderer = std::make_unique<tspgl::VolumeRenderer>(*ctx, *file, tsp::CachePolicy::on);
  renderer->set_transfer_function(tf);
  baseline = std::make_unique<tspgl::BaselineRenderer>(*ctx, *file);
  baseline->set_transfer_function(tf);
  metric = tsp::compute_errors(tsp::Metric::reference, file->tree(), tf, file.get(), 0);
  nodes = std::make_unique<tsp::WholeTreeMetric>(metric);
}

tsp::Camera FunctionScene::camera(tsp::CameraParams p) const {
  p.azimuth_deg = 30;
  p.elevation_deg = 20;
  p.width = ctx->width();
  p.height = ctx->height();
  return tsp::Camera(file->tree().octree().dims(), p);
}

}  // namespace tsptest

#include "support/function_scene.h"

#include "support/function_tsp.h"

namespace tsptest {

FunctionScene::FunctionScene(const std::string& name,
                             const std::function<float(int, int, int, int)>& f,
                             const tsp::TransferFunction& tf, tsp::Dims dims, int width, int height)
    : RenderScene(build_function_tsp(name, dims, f), tf, tsp::CachePolicy::on, width, height) {}

tsp::Camera FunctionScene::camera(tsp::CameraParams p) const {
  p.azimuth_deg = 30;
  p.elevation_deg = 20;
  p.width = ctx->width();
  p.height = ctx->height();
  return tsp::Camera(file->tree().octree().dims(), p);
}

}  // namespace tsptest

#include "support/render_scene.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "support/paths.h"
#include "tsp/build/build.h"
#include "tsp/report/image_diff.h"

namespace tsptest {

namespace fs = std::filesystem;

std::string build_tsp(tsp::VolumeSource& src, const std::string& name,
                      std::optional<tsp::ValueRange> range, int brick) {
  std::string path = (temp_dir() / (name + ".tsp")).string();
  tsp::BuildOptions o;
  o.brick_size = brick;
  o.range = range;
  tsp::build_tsp_file(src, path, o);
  return path;
}

std::string keep_failure(const std::string& name, const tsp::Image& actual,
                         const tsp::Image& expected) {
  fs::path dir = fs::current_path() / "test-output" / name;
  fs::create_directories(dir);
  tsp::write_png((dir / "actual.png").string(), actual);
  tsp::write_png((dir / "expected.png").string(), expected);
  tsp::Image diff;
  tsp::diff_images(actual, expected, &diff);
  tsp::write_png((dir / "difference.png").string(), diff);
  return dir.string();
}

void expect_close(const std::string& name, const tsp::Image& actual, const tsp::Image& expected,
                  double max_mean, double max_p99) {
  tsp::DiffStats d = tsp::diff_images(actual, expected);
  bool ok = d.mean < max_mean && d.p99 < max_p99;
  EXPECT_TRUE(ok) << name << ": mean ΔE " << d.mean << " (limit " << max_mean << "), p99 " << d.p99
                  << " (limit " << max_p99 << "), max " << d.max << "; images in "
                  << (ok ? "" : keep_failure(name, actual, expected));
}

tsp::TransferFunction flat_tf(tsp::Rgba c) {
  std::vector<tsp::TfPoint> pts = {{0.0, c}, {1.0, c}};
  return tsp::TransferFunction::from_points({0, 1}, pts);
}

RenderScene::RenderScene(const std::string& path, const tsp::TransferFunction& t,
                         tsp::CachePolicy cache, int w, int h, tsp::Metric m)
    : file(tsp::TspFile::open(path)), ctx(tspgl::create_offscreen_context(w, h)), tf(t) {
  renderer = std::make_unique<tspgl::VolumeRenderer>(*ctx, *file, cache);
  renderer->set_transfer_function(tf);
  baseline = std::make_unique<tspgl::BaselineRenderer>(*ctx, *file);
  baseline->set_transfer_function(tf);
  metric = tsp::compute_errors(m, file->tree(), tf, file.get(), 0);
}

tsp::Camera RenderScene::camera(double az, double el, bool perspective) const {
  tsp::CameraParams p;
  p.projection = perspective ? tsp::Projection::perspective : tsp::Projection::orthographic;
  p.azimuth_deg = az;
  p.elevation_deg = el;
  p.width = ctx->width();
  p.height = ctx->height();
  return tsp::Camera(file->tree().octree().dims(), p);
}

tsp::Image RenderScene::tsp_frame(int step, const tsp::Camera& cam, tsp::Tolerances tol) {
  tspgl::RenderSettings s;
  s.tol = tol;
  s.shade = shade;
  return frame(step, cam, s);
}

tsp::Image RenderScene::frame(int step, const tsp::Camera& cam, const tspgl::RenderSettings& s) {
  renderer->render(step, cam, s, nodes);
  return ctx->read_pixels();
}

tsp::Image RenderScene::baseline_frame(int step, const tsp::Camera& cam) {
  tspgl::RenderSettings s;
  s.shade = shade;
  baseline->render(step, cam, s);
  return ctx->read_pixels();
}

}  // namespace tsptest

#include "jobs/render_job.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "jobs/calibration.h"
#include "render/baseline_renderer.h"
#include "render/volume_renderer.h"
#include "tsp/core/error.h"
#include "tsp/core/file_check.h"
#include "tsp/core/json_text.h"
#include "tsp/core/stopwatch.h"
#include "tsp/core/temp_output.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json frame_json(const FrameRecord& f) {
  const FrameReport& r = f.report;
  return {{"pass", f.pass},
          {"step", r.step},
          {"ms", r.ms},
          {"traversal_ms", r.traversal_ms},
          {"slicing_ms", r.slicing_ms},
          {"upload_ms", r.upload_ms},
          {"draw_ms", r.draw_ms},
          {"not_rendered", r.class_percent[0]},
          {"untextured", r.class_percent[1]},
          {"reused_texture", r.class_percent[2]},
          {"new_texture", r.class_percent[3]},
          {"bytes_uploaded", r.bytes_uploaded},
          {"textures_resident", r.textures_resident},
          {"texture_bytes", r.texture_bytes},
          {"polygons", r.polygons},
          {"boxes", r.boxes},
          {"fragments", r.fragments},
          {"redrawn_percent", r.redrawn_percent}};
}

std::string step_png(const fs::path& dir, int step) {
  char name[32];
  std::snprintf(name, sizeof name, "step_%04d.png", step);
  return (dir / name).string();
}

}  // namespace

int checked_last_step(const tsp::TspTree& tree, int first, int last, const std::string& path) {
  const int steps = tree.time().steps();
  if (last < 0) last = steps - 1;
  if (first < 0 || first > last || last >= steps)
    throw tsp::UsageError("--steps " + std::to_string(first) + ":" + std::to_string(last) + ": " +
                          path + " has steps 0.." + std::to_string(steps - 1));
  return last;
}

double median_frame_ms(const RenderJobResult& result, int pass) {
  std::vector<double> ms;
  for (const FrameRecord& f : result.frames)
    if (pass == 0 || f.pass == pass) ms.push_back(f.report.ms);
  if (ms.empty()) return 0;
  std::nth_element(ms.begin(), ms.begin() + std::ptrdiff_t(ms.size() / 2), ms.end());
  return ms[ms.size() / 2];
}

namespace {

// o with the knobs --quality picks; fills the result's quality fields.
RenderJobOptions with_quality(RenderJobOptions o, RenderJobResult& result,
                              const CalibrationProgress& progress) {
  if (!(o.quality > 0) || !(o.quality <= kMaxQualityDe))
    throw tsp::UsageError("--quality " + std::to_string(o.quality) +
                          ": expected a mean dE in (0, " + std::to_string(int(kMaxQualityDe)) + "]");
  CalibrationRequest r;
  r.tsp_path = o.tsp_path;
  r.tf = o.tf;
  r.metric = o.metric;
  r.camera = o.camera;
  r.cache_dir = o.calibration_dir;
  const Calibration c = calibrate(r, &result.calibration_file, progress);
  const auto best = pick_configuration(c, o.quality);
  if (!best) {
    double lowest = 1e300;
    for (const CalibrationPoint& p : c.points) lowest = std::min(lowest, p.max_step_de);
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "--quality %g: no configuration stays within mean dE %g (with a %g margin) on "
                  "every calibration step; the closest reaches %.3g, so --quality %.3g is the "
                  "least that works (or use --spacing and tolerances directly)",
                  o.quality, o.quality * kQualityMargin, kQualityMargin, lowest,
                  lowest / kQualityMargin);
    throw tsp::UsageError(o.tsp_path + ": " + buf);
  }
  o.compositing = best->knobs.compositing;
  o.spacing = best->knobs.spacing;
  o.tol = {best->knobs.tol, best->knobs.tol};
  o.preintegrated = best->knobs.preintegrated;
  o.baseline = false;
  result.quality_options = render_options(best->knobs, o.metric);
  result.quality_calibrated_de = best->max_step_de;
  return o;
}

}  // namespace

RenderJobResult run_render_job(const RenderJobOptions& options, const RenderProgress& progress,
                               const CalibrationProgress& calibration_progress) {
  RenderJobResult result;
  const RenderJobOptions o =
      options.quality != 0 ? with_quality(options, result, calibration_progress) : options;
  // Options first: nothing is opened or rendered with a bad one.
  if (o.passes < 1 || o.passes > kMaxPasses)
    throw tsp::UsageError("--passes " + std::to_string(o.passes) + ": expected 1 to " +
                          std::to_string(kMaxPasses));
  RenderSettings settings;
  settings.tol = o.tol;
  settings.spacing = o.spacing;
  settings.compositing = o.compositing;
  settings.exact_flat = o.exact_flat;
  settings.span_step = o.span_step;
  settings.preintegrated = o.preintegrated;
  settings.reuse_image = o.reuse_image;
  validate(settings);
  validate_budget(o.texture_budget, "--texture-budget");
  auto file = tsp::TspFile::open(o.tsp_path);
  const tsp::TspTree& tree = file->tree();
  const int last = checked_last_step(tree, o.first_step, o.last_step, o.tsp_path);
  const tsp::TransferFunction tf = tsp::transfer_function_from_arg(o.tf, tree.value_range());
  if (!o.save_tf.empty()) {
    tsp::require_not_an_input(o.save_tf, {o.tsp_path, o.tf});
    tsp::save_transfer_function(tf, o.save_tf);
  }

  fs::path dir;
  if (!o.out_dir.empty()) {
    dir = o.out_dir;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw tsp::IoError(o.out_dir + ": cannot create the output directory: " + ec.message());
  }

  tsp::MetricResult metric;
  if (!o.baseline) {
    const tsp::Stopwatch watch;
    metric = tsp::compute_errors(o.metric, tree, tf, file.get(), 0);
    result.metric_ms = watch.ms();
  }
  auto ctx = create_offscreen_context(o.camera.width, o.camera.height);
  result.renderer = ctx->describe();
  std::unique_ptr<VolumeRenderer> renderer;
  std::unique_ptr<BaselineRenderer> baseline;
  if (o.baseline)
    baseline = std::make_unique<BaselineRenderer>(*ctx, *file);
  else
    renderer = std::make_unique<VolumeRenderer>(*ctx, *file, o.cache, o.texture_budget);
  if (baseline) baseline->set_transfer_function(tf);
  if (renderer) renderer->set_transfer_function(tf);
  tsp::WholeTreeMetric nodes(metric);
  const tsp::Camera camera(tree.octree().dims(), o.camera);
  const int total = o.passes * (last - o.first_step + 1);
  for (int pass = 1; pass <= o.passes; ++pass) {
    for (int t = o.first_step; t <= last; ++t) {
      FrameRecord rec;
      rec.pass = pass;
      rec.report = baseline ? baseline->render(t, camera, settings)
                            : renderer->render(t, camera, settings, nodes);
      result.frames.push_back(rec);
      // The last pass's images win; earlier passes only measure.
      if (!dir.empty() && o.write_images && pass == o.passes)
        tsp::write_png(step_png(dir, t), ctx->read_pixels());
      if (progress) progress(int(result.frames.size()), total);
    }
  }

  if (!dir.empty()) {
    json j;
    j["frames"] = json::array();
    for (const FrameRecord& f : result.frames) j["frames"].push_back(frame_json(f));
    j["file"] = o.tsp_path;
    j["renderer"] = result.renderer;
    j["mode"] = o.baseline ? "baseline" : "tsp";
    j["metric"] = o.baseline ? "none" : tsp::to_string(o.metric);
    j["metric_ms"] = result.metric_ms;
    j["cache"] = o.cache == tsp::CachePolicy::on ? "on" : "off";
    j["spatial_tol"] = o.tol.spatial;
    j["temporal_tol"] = o.tol.temporal;
    j["size"] = {o.camera.width, o.camera.height};
    j["view"] = {o.camera.azimuth_deg, o.camera.elevation_deg};
    j["projection"] = o.camera.projection == tsp::Projection::perspective ? "perspective"
                                                                          : "orthographic";
    j["spacing"] = o.spacing;
    j["compositing"] = to_string(o.compositing);
    j["flat"] = o.exact_flat ? "exact" : "slices";
    j["span_step"] = tsp::to_string(o.span_step);
    j["preintegrated"] = o.preintegrated;
    j["reuse"] = o.reuse_image;
    if (o.quality > 0)
      j["quality"] = {{"target_delta_e", o.quality},
                      {"render_options", result.quality_options},
                      {"calibrated_max_step_delta_e", result.quality_calibrated_de},
                      {"calibration_file", result.calibration_file}};
    j["median_ms"] = median_frame_ms(result, o.passes);
    tsp::write_file_atomically((dir / "frames.json").string(), tsp::json_text(j, 2) + "\n");
  }
  return result;
}

}  // namespace tspgl

#include "jobs/render_job.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "jobs/annotate.h"
#include "jobs/calibration.h"
#include "jobs/movie.h"
#include "jobs/visible_range.h"
#include "render/settings_table.h"
#include "render/baseline_renderer.h"
#include "render/mesh_surface.h"
#include "render/volume_renderer.h"
#include "tsp/core/error.h"
#include "tsp/core/interrupt.h"
#include "tsp/core/json_text.h"
#include "tsp/frame/exaggeration.h"
#include "tsp/core/memory_use.h"
#include "tsp/core/stopwatch.h"
#include "tsp/core/output_folder.h"
#include "tsp/core/temp_output.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

}  // namespace

void to_json(nlohmann::json& j, const FrameRecord& f) {
  j = f.report;
  j["pass"] = f.pass;
  j["azimuth_deg"] = f.azimuth_deg;
  j["ram_mib"] = double(f.ram_bytes) / (1 << 20);
  j["rss_mib"] = double(f.rss_bytes) / (1 << 20);
  j["time"] = f.time ? json(*f.time) : json(nullptr);
  j["time_text"] = f.time ? json(f.time_text) : json(nullptr);
  j["lod"] = nullptr;
  if (f.lod) {
    j["lod"] = f.lod->stats;
    j["lod"]["target_ms"] = f.lod->target_ms;
  }
  if (f.rank >= 0) j["rank"] = f.rank;
  if (f.surface_splats >= 0) {
    j["surface_splats"] = f.surface_splats;
    j["surface_cut_ms"] = f.surface_cut_ms;
    j["surface_ms"] = f.surface_ms;
    j["surface_px"] = f.surface_px;
  }
}


fs::path make_output_dir(const std::string& out) {
  // The folder is made, its parent must exist (as for build's -o): a mistyped path fails
  // instead of growing a tree of folders.
  const fs::path dir = out;
  std::error_code ec;
  fs::path full = fs::absolute(dir, ec).lexically_normal();
  if (full.filename().empty()) full = full.parent_path();  // "frames/"
  const fs::path parent = full.parent_path();
  if (!fs::is_directory(parent, ec))
    throw tsp::IoError(out + ": directory " + parent.string() + " does not exist");
  fs::create_directory(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw tsp::IoError(out + ": cannot create the output directory" +
                       (ec ? ": " + ec.message() : std::string()));
  return dir;
}

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
  return median(std::move(ms));
}

namespace {

// o with the knobs --quality picks for file under tf; fills the result's quality fields.
RenderJobOptions with_quality(GlContext& ctx, RenderJobOptions o, const tsp::TspFile& file,
                              const tsp::TransferFunction& tf, RenderJobResult& result,
                              const CalibrationProgress& progress) {
  CalibrationRequest r;
  r.tsp_path = o.tsp_path;
  r.field = file.fields()[std::size_t(file.field_index())];
  r.metric = o.metric;
  r.camera = o.camera;
  r.cache_dir = o.calibration_dir;
  const Calibration c = calibrate(ctx, r, file, tf, &result.calibration_file, progress);
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
  apply(best->knobs, o.settings);
  o.baseline = false;
  result.quality_options = render_options(best->knobs, o.metric);
  result.quality_calibrated_de = best->max_step_de;
  return o;
}

}  // namespace

std::array<double, 3> shown_voxel_size(const std::array<double, 3>& spacing,
                                       const std::array<double, 3>& scale, bool physical) {
  std::array<double, 3> v{};
  for (std::size_t a = 0; a < 3; ++a) {
    const double s = physical && std::isfinite(spacing[a]) && spacing[a] > 0 ? spacing[a] : 1.0;
    v[a] = s * scale[a];
  }
  return v;
}

void place_field(tsp::CameraParams& c, const tsp::TspFile& file, const std::array<double, 3>& scale,
                 bool physical) {
  c.voxel_size = shown_voxel_size(file.metadata().spacing, scale, physical);
  c.origin = {0, 0, 0};
  c.frame = tsp::empty_aabb();
  if (!physical || file.fields().size() < 2) return;
  const tsp::Aabb& f = file.frame();
  for (std::size_t a = 0; a < 3; ++a) {
    const double k = c.voxel_size[a] / file.metadata().spacing[a];  // the scale, or 1/spacing
    c.origin[a] = file.metadata().origin[a] * k;
    c.frame.lo[a] = f.lo[a] * k;
    c.frame.hi[a] = f.hi[a] * k;
  }
}

namespace {

// The options' checks that need no file.
void check_options(const RenderJobOptions& o) {
  if (o.quality != 0 && !(o.quality > 0 && o.quality <= kMaxQualityDe))
    throw tsp::UsageError("--quality " + std::to_string(o.quality) +
                          ": expected a mean dE in (0, " + std::to_string(int(kMaxQualityDe)) + "]");
  if (o.passes < 1 || o.passes > kMaxPasses)
    throw tsp::UsageError("--passes " + std::to_string(o.passes) + ": expected 1 to " +
                          std::to_string(kMaxPasses));
  validate(o.settings);
  validate_budget(o.texture_budget, "--texture-budget");
  validate_budget(o.ram_budget, "--ram-budget");
  if (!(o.target_ms >= 0) || o.target_ms > kMaxTargetMs)
    throw tsp::UsageError("--target-ms " + std::to_string(o.target_ms) +
                          ": expected a frame time in (0, " + std::to_string(int(kMaxTargetMs)) +
                          "] ms");
  if (o.target_ms > 0 && o.lod != LodMode::adaptive)
    throw tsp::UsageError("--target-ms needs --lod auto (the adaptive cut holds the target)");
  if (o.lod != LodMode::off && o.baseline)
    throw tsp::UsageError("--lod is for the TSP renderer: drop --baseline");
  if (!o.probes.empty() && o.baseline)
    throw tsp::UsageError("--probe is for the TSP renderer: drop --baseline");
  if ((o.probe_surface || !o.probe_tf.empty() ||
       o.probe_motion != std::array<double, 3>{0, 0, 0}) &&
      o.probes.empty())
    throw tsp::UsageError("--probe-surface/--probe-tf/--probe-motion need a --probe");
  for (double d : o.probe_motion)
    if (!std::isfinite(d)) throw tsp::UsageError("--probe-motion: expected finite numbers");
  if (o.lod == LodMode::fixed && o.lod_level < 0)
    throw tsp::UsageError("--lod " + std::to_string(o.lod_level) +
                          ": expected off, auto or a level >= 0");
  if (!std::isfinite(o.orbit_deg) || std::fabs(o.orbit_deg) > 360)
    throw tsp::UsageError("--orbit " + std::to_string(o.orbit_deg) +
                          ": expected degrees per frame in [-360, 360]");
  for (double k : o.scale)
    if (!(k > 0) || !(k <= kMaxScale))
      throw tsp::UsageError("--scale: expected three factors in (0, " +
                            std::to_string(int(kMaxScale)) + "], found " + std::to_string(k));
  if (!o.settings.surface &&
      (!o.surface_mesh.empty() || !o.surface_field.empty() || !o.surface_tf.empty()))
    throw tsp::UsageError("--surface-mesh/--surface-field/--surface-tf need --surface boundary");
  if (o.settings.surface && o.surface_mesh.empty())
    throw tsp::UsageError("--surface boundary needs --surface-mesh, the mesh series the file was "
                          "built from");
  if (o.settings.surface && o.settings.compositing != Compositing::rays)
    throw tsp::UsageError("--surface boundary is drawn with --compositing rays");
  if (!(o.surface_target_ms >= 0) || o.surface_target_ms > kMaxTargetMs)
    throw tsp::UsageError("--surface-target-ms " + std::to_string(o.surface_target_ms) +
                          ": expected a time in (0, " + std::to_string(int(kMaxTargetMs)) + "] ms");
  if (o.surface_target_ms > 0 && !o.settings.surface)
    throw tsp::UsageError("--surface-target-ms needs --surface boundary");
  if (o.step_stride < 1)
    throw tsp::UsageError("--steps: the stride must be 1 or more, got " +
                          std::to_string(o.step_stride));
  if (o.parts < 0 || (o.parts > 0 && (o.part < 0 || o.part >= o.parts)))
    throw tsp::UsageError("part " + std::to_string(o.part) + " of " +
                          std::to_string(o.parts) + ": expected 0 <= part < parts");
}

// The LOD cut the driver draws with: --lod K (clamped to the file's levels), auto, splats or a
// selection filter.
LodSpec lod_spec(const RenderJobOptions& o, int lod_level) {
  LodSpec lod;
  lod.mode = o.lod;
  lod.level = lod_level;
  lod.splat_px = o.splat_px;
  lod.filter = o.lod_filter;
  lod.options = o.lod_options;
  lod.options.target_ms = o.target_ms;
  if (lod.options.texture_budget == 0) lod.options.texture_budget = o.texture_budget;
  lod.converge = o.target_ms <= 0;  // untimed: a converged cut every frame
  return lod;
}

// The surface pass's figures into rec; with --surface-target-ms, the next frame's splat size:
// splats ∝ 1 / size², so the size that would have taken the target, a step at a time.
void record_surface(const SurfaceStats& ss, const RenderJobOptions& o, FrameRecord& rec,
                    double& surface_px) {
  rec.surface_splats = ss.splats;
  rec.surface_cut_ms = ss.cut_ms;
  rec.surface_ms = ss.ms;
  rec.surface_px = surface_px;
  if (o.surface_target_ms > 0 && ss.ms > 0)
    surface_px = std::clamp(surface_px * std::clamp(std::sqrt(ss.ms / o.surface_target_ms),
                                                    1 / kSurfacePxStep, kSurfacePxStep),
                            kMinSurfacePx, kMaxSurfacePx);
}

// frames.json: every frame and what the frames were drawn with.
json frames_json(const RenderJobOptions& o, const RenderJobResult& result,
                 const tsp::TspFile& file, int lod_level) {
  const tsp::TspTree& tree = file.tree();
  const RenderSettings& settings = o.settings;
  json j;
  j["frames"] = json::array();
  for (const FrameRecord& f : result.frames) j["frames"].push_back(f);
  j["file"] = o.tsp_path;
  j["renderer"] = result.renderer;
  j["gl_vendor"] = result.gl_vendor;
  j["context"] = result.context;
  j["mode"] = o.baseline ? "baseline" : "tsp";
  j["metric"] = o.baseline ? "none" : tsp::to_string(o.metric);
  j["metric_ms"] = result.metric_ms;
  j["cache"] = o.cache == tsp::CachePolicy::on ? "on" : "off";
  j["size"] = {o.camera.width, o.camera.height};
  j["view"] = {o.camera.azimuth_deg, o.camera.elevation_deg};
  j["projection"] = o.camera.projection == tsp::Projection::perspective ? "perspective"
                                                                        : "orthographic";
  j.update(settings_json(settings));  // every knob of the settings table
  j["lod"] = o.lod == LodMode::off     ? json("off")
             : o.lod == LodMode::fixed ? json(lod_level)
             : o.lod == LodMode::splat ? json("splat:" + json(o.splat_px).dump())
             : o.lod == LodMode::filter ? json("filter")
                                        : json("auto");
  j["lod_filter"] = o.lod == LodMode::filter ? tsp::to_string(o.lod_filter.kind) : "error";
  j["lod_filter_k"] = o.lod_filter.scale;
  if (o.camera.eye) j["eye"] = *o.camera.eye;
  j["target_ms"] = o.target_ms;
  j["lod_fallback"] = tsp::to_string(o.lod_options.fallback);
  j["orbit_deg"] = o.orbit_deg;
  j["lod_levels"] = tree.octree().max_lod_level() + 1;
  if (o.settings.surface) {
    j["surface_mesh"] = o.surface_mesh;
    j["surface_field"] = o.surface_field.empty() ? file.metadata().field : o.surface_field;
    j["surface_target_ms"] = o.surface_target_ms;
  }
  if (o.quality > 0)
    j["quality"] = {{"target_delta_e", o.quality},
                    {"render_options", result.quality_options},
                    {"calibrated_max_step_delta_e", result.quality_calibrated_de},
                    {"calibration_file", result.calibration_file}};
  j["median_ms"] = median_frame_ms(result, o.passes);
  return j;
}

}  // namespace

namespace {

// What draws the job's frames: the TSP renderer (with the metric, the clip solid and the mesh's
// surface) or the non-TSP baseline, and the one frame driver over it.
class FrameSource {
 public:
  FrameSource(GlContext& ctx, const RenderJobOptions& o, tsp::TspFile& file,
              const tsp::TransferFunction& tf, const tsp::TransferFunction& probe_tf,
              int lod_level, RenderJobResult& result)
      : o_(o), file_(file) {
    if (o.baseline) {
      baseline_ = std::make_unique<BaselineRenderer>(ctx, file, o.ram_budget);
      baseline_->set_transfer_function(tf);
      nodes_.emplace(metric_);
      driver_ = std::make_unique<FrameDriver>(*baseline_);
      return;
    }
    const tsp::Stopwatch watch;
    metric_ = tsp::compute_errors(o.metric, file.tree(), tf, &file, 0);
    result.metric_ms = watch.ms();
    nodes_.emplace(metric_);
    renderer_ = std::make_unique<VolumeRenderer>(ctx, file, o.cache, o.texture_budget,
                                                 o.ram_budget);
    renderer_->set_transfer_function(tf);
    if (o.probe_surface) probe_tf_ = probe_tf;
    // The mesh's boundary under the volume: its splat hierarchy per step, coloured by its TF.
    if (o.settings.surface)
      mesh_surface_.emplace(o.surface_mesh, o.surface_field, file, o.surface_tf, o.first_step);
    if (!o.probes.empty()) place_probes(0);
    driver_ = std::make_unique<FrameDriver>(*renderer_, lod_spec(o, lod_level));
  }

  /// The mesh surface's legend bar (none without --surface boundary).
  SurfaceLegend surface_legend() const {
    return mesh_surface_ ? SurfaceLegend{&mesh_surface_->tf(), mesh_surface_->field()}
                         : SurfaceLegend{};
  }

  /// The node errors the frames read (empty for the baseline).
  tsp::FrameMetric* metric() { return &*nodes_; }

  /// The clip solid of frame `frame`, in the file's physical coordinates: with probe_motion
  /// its probes move every frame (a plane along its normal's share of the motion).
  void place_probes(int frame) {
    if (o_.probes.empty() ||
        (frame > 0 && o_.probe_motion == std::array<double, 3>{0, 0, 0}))
      return;
    std::vector<tsp::Probe> probes = o_.probes;
    for (tsp::Probe& p : probes)
      tsp::move_probe(p, {o_.probe_motion[0] * frame, o_.probe_motion[1] * frame,
                          o_.probe_motion[2] * frame});
    renderer_->set_clip(tsp::ClipRegion(probes, o_.probe_op, file_.metadata().origin,
                                        file_.metadata().spacing),
                        probe_tf_);
  }

  /// Another part's frame: only what carries over to the next (the LOD cut).
  void advance(const FrameRequest& request) { driver_->advance(request); }

  /// Draws step request.step into rec (its report, LOD, surface and memory figures).
  void draw(const FrameRequest& request, FrameRecord& rec) {
    SliceCompositor& compositor =
        baseline_ ? baseline_->compositor() : *renderer_->compositor();
    if (mesh_surface_) compositor.set_surface(mesh_surface_->frame(request.step, surface_px_));
    const DrawnFrame drawn = driver_->draw(request);
    if (mesh_surface_) record_surface(compositor.surface_stats(), o_, rec, surface_px_);
    rec.report = drawn.report;
    if (drawn.lod)
      rec.lod = LodRecord{o_.lod == LodMode::adaptive ? o_.target_ms : 0, *drawn.lod};
    rec.ram_bytes = (baseline_ ? baseline_->brick_cache() : renderer_->brick_cache())
                        .stats()
                        .resident_bytes;
    rec.rss_bytes = tsp::resident_bytes();
  }

 private:
  const RenderJobOptions& o_;
  tsp::TspFile& file_;
  tsp::MetricResult metric_;
  std::optional<tsp::WholeTreeMetric> nodes_;
  std::unique_ptr<VolumeRenderer> renderer_;
  std::unique_ptr<BaselineRenderer> baseline_;
  std::optional<tsp::TransferFunction> probe_tf_;  ///< the clip surface's colours (if drawn)
  std::optional<MeshSurface> mesh_surface_;
  double surface_px_ = o_.settings.surface_px;  ///< the cut's minimum splat size (adapts)
  std::unique_ptr<FrameDriver> driver_;
};

// The job's input: the file, its last step, and the TF and where it sits.
struct JobInput {
  std::unique_ptr<tsp::TspFile> file;
  int last = 0;
  tsp::ValueRange tf_domain;
  tsp::ValueHistogram histogram;
  std::optional<tsp::TransferFunction> tf;
};

// Opens the file and builds the TF; places the camera (physical proportions: the file's voxel
// spacing, times --scale, shapes the view).
JobInput open_input(RenderJobOptions& options) {
  JobInput in;
  in.file = tsp::TspFile::open(options.tsp_path, options.field);
  const tsp::TspFile& file = *in.file;
  const tsp::TspTree& tree = file.tree();
  place_field(options.camera, file, options.scale, options.physical_proportions);
  in.last = checked_last_step(tree, options.first_step, options.last_step, options.tsp_path);
  // Where the TF sits: --tf-range visible takes what this view shows of the first step.
  in.tf_domain =
      options.tf_range.mode == tsp::TfRangeChoice::Mode::visible
          ? visible_value_range(tree, options.first_step,
                                tsp::Camera(tree.octree().dims(), options.camera),
                                tsp::ClipRegion(options.probes, options.probe_op,
                                                file.metadata().origin, file.metadata().spacing))
          : tsp::tf_domain_of(options.tf_range, file, options.first_step);
  in.histogram = tsp::histogram_of(file);
  in.tf = tsp::transfer_function_from_arg(options.tf, in.tf_domain, tsp::kDefaultTfEntries,
                                          options.tf_range, &in.histogram);
  return in;
}

// Writes into the job's folder; a write that fails (a full disk) names the folder the user
// gave, not its hidden temporary.
template <typename Write>
void into_folder(const tsp::OutputFolder& folder, const Write& write) {
  try {
    write();
  } catch (const tsp::IoError& e) {
    throw tsp::IoError(folder.as_shown(e.what()));
  }
}

// Draws every frame of the job (all passes; a split render's part draws its own block and
// replays the others' cuts) into result, and the last pass's PNGs into the folder.
void draw_frames(GlContext& ctx, const RenderJobOptions& o, const JobInput& in, int lod_level,
                 const tsp::OutputFolder* folder, const RenderProgress& progress,
                 RenderJobResult& result) {
  const tsp::TspFile& file = *in.file;
  const tsp::TspTree& tree = file.tree();
  const tsp::TransferFunction& tf = *in.tf;
  const tsp::TransferFunction probe_tf =
      o.probe_surface && !o.probe_tf.empty()
          ? tsp::transfer_function_from_arg(o.probe_tf, in.tf_domain, tsp::kDefaultTfEntries,
                                            o.tf_range, &in.histogram)
          : tf;
  FrameSource source(ctx, o, *in.file, tf, probe_tf, lod_level, result);
  const int per_pass = (in.last - o.first_step) / o.step_stride + 1;
  // A split render's part draws frames [block.first, block.second) of every pass.
  const auto block = o.parts > 0 ? part_frames(per_pass, o.part, o.parts)
                                 : std::pair<int, int>{0, per_pass};
  const int total = o.passes * (block.second - block.first);
  int frame_index = 0;
  for (int pass = 1; pass <= o.passes; ++pass) {
    for (int t = o.first_step; t <= in.last; t += o.step_stride, ++frame_index) {
      tsp::throw_if_interrupted();
      const int in_pass = (t - o.first_step) / o.step_stride;
      const bool mine = in_pass >= block.first && in_pass < block.second;
      // Another part's frame: skipped, or with a cut that carries over, replayed (up to this
      // part's last frame) so that this part's frames are drawn with the whole render's cuts.
      if (!mine && (pass == o.passes && in_pass >= block.second)) continue;
      tsp::CameraParams params = o.camera;
      params.azimuth_deg += o.orbit_deg * frame_index;
      const tsp::Camera camera(tree.octree().dims(), params);
      if (frame_index > 0) source.place_probes(frame_index);  // (frame 0's: set up)
      FrameRequest request;
      request.step = t;
      request.camera = &camera;
      request.settings = o.settings;
      request.metric = source.metric();
      request.tf = &tf;
      if (!mine) {
        source.advance(request);
        continue;
      }
      FrameRecord rec;
      rec.pass = pass;
      if (o.parts > 0) rec.rank = o.part;
      rec.azimuth_deg = params.azimuth_deg;
      if (!file.metadata().times.empty()) {
        rec.time = file.metadata().times[std::size_t(t)];
        rec.time_text = tsp::format_time(*rec.time, file.metadata().time_units);
      }
      source.draw(request, rec);
      // A frame the chosen back end cannot draw is drawn by the other: said once, and in the
      // frame's record (caster_note).
      if (!rec.report.backend_note.empty() &&
          std::find(result.warnings.begin(), result.warnings.end(), rec.report.backend_note) ==
              result.warnings.end())
        result.warnings.push_back(rec.report.backend_note);
      result.frames.push_back(rec);
      // The last pass's images win; earlier passes only measure.
      const bool png = folder && o.write_images && pass == o.passes;
      if (png || o.on_frame) {
        tsp::Image pixels = ctx.read_pixels();
        if (o.annotate)
          annotate_frame(pixels, camera, tree.octree().dims(), tf, t,
                         rec.time ? std::optional<std::string>(rec.time_text) : std::nullopt,
                         file.fields()[std::size_t(file.field_index())],
                         o.physical_proportions ? tsp::exaggeration_text(o.scale, true) : "",
                         source.surface_legend());
        if (o.on_frame) o.on_frame(rec, pixels);
        if (png)
          into_folder(*folder, [&] { tsp::write_png(step_png(folder->tmp(), t), pixels); });
      }
      if (progress) progress(int(result.frames.size()), total);
    }
  }
}

}  // namespace

RenderJobResult run_render_job(const RenderJobOptions& requested, const RenderProgress& progress,
                               const CalibrationProgress& calibration_progress) {
  RenderJobOptions options = requested;
  check_options(options);  // nothing is opened or rendered with a bad option
  const JobInput in = open_input(options);
  const tsp::TransferFunction& tf = *in.tf;
  // Every output is checked before any work and replaced only when the whole job succeeded.
  const tsp::InputGuard inputs({options.tsp_path, options.tf, options.probe_tf, options.surface_mesh,
                                options.surface_tf});
  std::optional<tsp::OutputFolder> folder;
  if (!options.out_dir.empty()) folder.emplace(options.out_dir, is_frame_set_name);
  std::optional<tsp::TempOutput> saved_tf, movie;
  if (!options.save_tf.empty()) {
    saved_tf.emplace(options.save_tf);
    tsp::save_transfer_function(tf, saved_tf->tmp());
  }
  if (!options.movie.empty()) {
    if (options.out_dir.empty()) throw tsp::UsageError("--movie needs -o, the frames' folder");
    check_movie_name(options.movie, "--movie");
    movie.emplace(options.movie);
  }
  RenderJobResult result;
  if (std::string w = tsp::tf_range_warning(tf, in.file->metadata().data_range); !w.empty())
    result.warnings.push_back(w);
  if (options.check_only && options.quality == 0) return result;
  std::string gl_note;
  auto ctx = create_headless_context(options.camera.width, options.camera.height, options.gl,
                                     options.gpu, &gl_note);
  if (!gl_note.empty()) result.warnings.push_back(gl_note);
  result.renderer = ctx->describe();
  result.gl_vendor = ctx->vendor();
  result.context = ctx->kind();
  const RenderJobOptions o =
      options.quality != 0 ? with_quality(*ctx, options, *in.file, tf, result, calibration_progress)
                           : options;
  if (options.check_only) return result;  // the calibration is cached for the parts
  // --lod K, clamped to the file's levels (what frames.json records too).
  const int lod_level = std::min(o.lod_level, in.file->tree().octree().max_lod_level());
  draw_frames(*ctx, o, in, lod_level, folder ? &*folder : nullptr, progress, result);
  if (folder) {
    const json j = frames_json(o, result, *in.file, lod_level);
    into_folder(*folder, [&] {
      tsp::write_file_atomically((fs::path(folder->tmp()) / "frames.json").string(),
                                 tsp::json_text(j, 2) + "\n");
    });
  }
  if (movie) {  // the last pass's frames, in the order rendered
    std::vector<fs::path> frames;
    for (const FrameRecord& f : result.frames)
      if (f.pass == o.passes) frames.push_back(step_png(folder->tmp(), f.report.step));
    encode_movie_into(frames, *movie, o.movie, o.fps);
  }
  if (saved_tf) saved_tf->commit();
  if (folder) folder->commit();
  if (movie) movie->commit();
  return result;
}

}  // namespace tspgl

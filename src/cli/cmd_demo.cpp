// tspplay demo: the README's main job. Generates the built-in dataset, builds its TSP tree,
// summarises it, and writes a report; files already made are reused.
#include <cstdlib>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <unistd.h>

#include "cli/args.h"
#include "cli/build_runner.h"
#include "cli/commands.h"
#include "cli/info_report.h"
#include "jobs/movie.h"
#include "jobs/render_job.h"
#include "jobs/timing.h"
#include "player/player.h"
#include "render/settings_table.h"
#include "tsp/core/error.h"
#include "tsp/core/json_text.h"
#include "tsp/core/stopwatch.h"
#include "tsp/core/temp_output.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"
#include "tsp/source/open_source.h"
#include "tsp/source/procedural/generate.h"
#include "tsp/store/tsp_file.h"

namespace tspcli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct DemoArgs {
  std::string dir = "tspplay-demo";
  std::string dataset = "shock";
  std::string dims, steps;
  bool force = false;
  bool no_play = false;
};

// The player opens only for a person at a terminal with a display: scripts, CI and tests
// (stdin from /dev/null) stay headless even under Xvfb.
bool interactive_display() {
  const char* x = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return ((x && *x) || (w && *w)) && isatty(STDIN_FILENO) && isatty(STDOUT_FILENO);
}

// Bricks of 16 samples: on the 64³ default they skip much more empty space than 32 (docs/results.md).
constexpr int kDemoBrick = 16;
// What the tree buys, stated: its frames at this spatial and temporal tolerance and sample
// spacing (docs/results.md, "The demo"), against the baseline at full quality, within this mean
// ΔE of it.
constexpr double kDemoTolerance = 0.02, kDemoSpacing = 1, kDemoTargetDeltaE = 1;

// "N.Nx faster" or "N.Nx slower" for a ratio of frame times (baseline / tsp).
std::string speed_words(double ratio) {
  char buf[64];
  if (ratio >= 1)
    std::snprintf(buf, sizeof buf, "%.1fx faster", ratio);
  else
    std::snprintf(buf, sizeof buf, "%.1fx slower", 1 / ratio);
  return buf;
}

// True when `out` exists and is at least as new as `in`: the step that makes it can be skipped.
bool up_to_date(const fs::path& out, const fs::path& in) {
  std::error_code ec;
  if (!fs::exists(out, ec)) return false;
  return in.empty() || fs::last_write_time(out, ec) >= fs::last_write_time(in, ec);
}

// Error statistics of one metric with the sparse preset, for the report.
json metric_summary(tsp::Metric metric, const tsp::TspFile& file, const tsp::TransferFunction& tf) {
  const tsp::Stopwatch watch;
  tsp::MetricResult r = tsp::compute_errors(metric, file.tree(), tf, &file, 0);
  const double ms = watch.ms();
  const int n = file.tree().size();
  const int transparent = r.transparent_count();
  return {{"metric", tsp::to_string(metric)},
          {"recompute_ms", ms},
          {"tsp_nodes", n},
          {"transparent_nodes", transparent},
          {"transparent_fraction", n ? double(transparent) / n : 0.0}};
}

// Renders every step with the TSP tree (at kDemoTolerance and kDemoSpacing) into DIR/frames and
// without it at full quality into DIR/baseline, headless, and compares them; returns the
// frame-time summary.
json render_frames(const fs::path& tsp_path, const fs::path& tf_path, const fs::path& dir) {
  tspgl::RenderJobOptions o;
  o.tsp_path = tsp_path.string();
  o.tf = tf_path.string();
  o.passes = 2;  // the second pass plays with the textures the first left in the cache
  o.annotate = true;  // outline, axes, colour legend and step on every frame (both renderers)
  json out;
  // How the frames were drawn: lighting, sampling, compositing, pre-integration (the defaults).
  out["settings"] = tspgl::settings_json(o.settings);
  tspgl::RenderSettings tsp_settings = o.settings;
  tsp_settings.tol = {kDemoTolerance, kDemoTolerance};
  tsp_settings.spacing = kDemoSpacing;
  out["tsp_settings"] = tspgl::settings_json(tsp_settings);
  std::printf("\nrendering %dx%d frames headless:\n", o.camera.width, o.camera.height);
  for (bool baseline : {false, true}) {
    o.baseline = baseline;
    o.settings = baseline ? tspgl::RenderSettings{} : tsp_settings;
    o.out_dir = (dir / (baseline ? "baseline" : "frames")).string();
    tspgl::RenderJobResult r = tspgl::run_render_job(o);
    const tspgl::Timing t = tspgl::timing_of(r, o.passes);
    const std::string caster = r.frames.empty() ? "" : r.frames.back().report.backend;
    std::printf("  %-9s median %7.2f ms a frame (first pass %7.2f ms, %s caster, %s) -> %s/\n",
                baseline ? "baseline" : "tsp", t.median_ms, t.first_pass_median_ms,
                caster.c_str(), r.context.c_str(), o.out_dir.c_str());
    // The run as bench's report.json writes one (jobs/timing.h), with where its frames went,
    // what drew them and who cast the last frame's rays (frames.json's "caster").
    json run = t;
    run.update({{"frames_dir", o.out_dir},
                {"renderer", r.renderer},
                {"context", r.context},
                {"caster", caster}});
    out[baseline ? "baseline" : "tsp"] = run;
  }
  const double speedup = double(out["baseline"]["median_ms"]) / double(out["tsp"]["median_ms"]);
  // Same picture? The worst step's mean and 99th-percentile ΔE between the two renderings.
  double worst_mean = 0, worst_p99 = 0;
  for (const auto& e : fs::directory_iterator(dir / "frames")) {
    if (e.path().extension() != ".png") continue;
    tsp::DiffStats d = tsp::diff_images(tsp::read_png(e.path().string()),
                                        tsp::read_png((dir / "baseline" / e.path().filename()).string()));
    worst_mean = std::max(worst_mean, d.mean);
    worst_p99 = std::max(worst_p99, d.p99);
  }
  std::printf("  tsp (tolerance %g, spacing %g) is %s than the baseline at full quality (spacing "
              "%g); worst step: mean dE %.3f (%s %g), p99 %.3f\n",
              kDemoTolerance, kDemoSpacing, speed_words(speedup).c_str(),
              tspgl::RenderSettings{}.spacing, worst_mean,
              worst_mean <= kDemoTargetDeltaE ? "within" : "misses", kDemoTargetDeltaE, worst_p99);
  out["speedup"] = speedup;
  out["target_delta_e"] = kDemoTargetDeltaE;
  out["worst_mean_delta_e"] = worst_mean;
  out["worst_p99_delta_e"] = worst_p99;
  return out;
}

// Encodes DIR/frames into DIR/demo.mp4 when ffmpeg is installed; returns its path or null.
// A failing encoder is reported, not fatal: the movie is an extra.
json make_movie(const fs::path& dir) {
  const fs::path movie = dir / "demo.mp4";
  try {
    std::vector<fs::path> frames;  // the rendered steps, in step order
    for (const auto& e : fs::directory_iterator(dir / "frames"))
      if (e.path().extension() == ".png") frames.push_back(e.path());
    std::sort(frames.begin(), frames.end());
    if (tspgl::encode_movie(frames, movie)) {
      std::printf("  movie: %s (%d frames a second)\n", movie.string().c_str(), tspgl::kMovieFps);
      return movie.string();
    }
    std::printf("  movie: skipped (no ffmpeg on PATH; the frames are in %s)\n",
                (dir / "frames").string().c_str());
  } catch (const tsp::Error& e) {
    std::printf("  movie: skipped (%s)\n", e.what());
  }
  return nullptr;
}

void run(const DemoArgs& a) {
  tsp::GenerateOptions gen;
  if (!a.dims.empty()) gen.dims = parse_dims(a.dims, "--dims", tsp::kMaxGeneratedEdge, true);
  if (!a.steps.empty())
    gen.steps = int(parse_integer(a.steps, "--steps", 1, tsp::kMaxGeneratedSteps,
                                  "a step count in [1, " +
                                      std::to_string(tsp::kMaxGeneratedSteps) + "]"));
  auto source = tsp::make_generated_source(a.dataset, gen);

  const fs::path dir = a.dir;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw tsp::IoError(dir.string() + ": cannot create the demo directory: " + ec.message());
  // Sizes and seed are part of the names, so a demo with other options never reuses stale files.
  const std::string stem = source->name() + "_" + tsp::to_string(source->dims()) + "_" +
                           std::to_string(source->steps());
  const fs::path h5 = dir / (stem + ".h5"), tsp_path = dir / (stem + ".tsp");
  const fs::path tf_path = dir / "auto_tf.json", report_path = dir / "report.json";
  json report;
  report["dataset"] = {{"name", source->name()},
                       {"dims", {source->dims().x, source->dims().y, source->dims().z}},
                       {"steps", source->steps()},
                       {"seed", source->seed()}};

  std::printf("tspplay demo: %s %s x %d steps in %s\n", source->name().c_str(),
              tsp::to_string(source->dims()).c_str(), source->steps(), dir.string().c_str());
  if (a.force || !up_to_date(h5, {})) {
    const tsp::Stopwatch watch;
    tsp::write_generated_dataset(*source, h5.string());
    report["generate_s"] = watch.seconds();
    std::printf("generated %s (%.2f s)\n", h5.string().c_str(), double(report["generate_s"]));
  } else {
    std::printf("reusing %s\n", h5.string().c_str());
  }

  if (a.force || !up_to_date(tsp_path, h5)) {
    // Built through the HDF5 reader, as a user's own file would be.
    tsp::SourceOptions so;
    so.field = source->name();
    auto input = tsp::open_source(h5.string(), so);
    tsp::BuildOptions bo;
    bo.field_name = so.field;
    bo.brick_size = kDemoBrick;
    tsp::BuildReport r = build_with_progress(*input, tsp_path.string(), bo);
    print_build_summary(tsp_path.string(), r);
    report["build"] = {{"seconds", r.seconds},
                       {"source_bytes", r.source_bytes},
                       {"mb_per_s", r.seconds > 0 ? double(r.source_bytes) / 1e6 / r.seconds : 0}};
  } else {
    std::printf("reusing %s\n", tsp_path.string().c_str());
  }

  auto file = tsp::TspFile::open(tsp_path.string());
  std::printf("\n");
  print_info(*file, false);
  json info = info_json(*file, false);
  info.erase("histogram");
  report["tree"] = info;

  // The default colour map (preset:auto: opacity where the data is rare, from the histogram),
  // saved so that metrics, render and play can be rerun on the same map.
  const tsp::ValueHistogram histogram = tsp::histogram_of(*file);
  const tsp::TransferFunction tf = tsp::preset_transfer_function(
      tsp::kAutoPreset, tsp::preset_domain(file->tree().value_range()), tsp::kDefaultTfEntries,
      &histogram);
  tsp::save_transfer_function(tf, tf_path.string());
  std::printf("\nerror metrics with the default colour map (%s):\n", tf_path.string().c_str());
  for (tsp::Metric m : {tsp::Metric::scalar, tsp::Metric::approximate, tsp::Metric::perceptual,
                        tsp::Metric::reference}) {
    json s = metric_summary(m, *file, tf);
    std::printf("  %-12s recompute %9.2f ms, %d of %d TSP nodes transparent\n",
                std::string(s["metric"]).c_str(), double(s["recompute_ms"]),
                int(s["transparent_nodes"]), int(s["tsp_nodes"]));
    report["metrics"].push_back(s);
  }
  report["render"] = render_frames(tsp_path, tf_path, dir);
  report["movie"] = make_movie(dir);
  tsp::write_file_atomically(report_path.string(), tsp::json_text(report, 2) + "\n");
  std::printf("\nwrote %s\nnext:\n  tspplay info %s --json --nodes\n  tspplay metrics %s --tf %s\n",
              report_path.string().c_str(), tsp_path.string().c_str(), tsp_path.string().c_str(),
              tf_path.string().c_str());
  if (!a.no_play && interactive_display()) {
    std::printf("\nopening the player (close the window to exit; --no-play to skip)\n");
    std::fflush(stdout);
    tspplayer::PlayerOptions po;
    po.tsp_path = tsp_path.string();
    po.tf = tf_path.string();
    tspplayer::run_player(po);
  }
}

const CommandRegistrar reg(1, [](CLI::App& app) {
  auto* c = app.add_subcommand(
      "demo", "Generate the built-in dataset, build its TSP tree and report (the README's job)");
  auto a = std::make_shared<DemoArgs>();
  c->add_option("-o,--output", a->dir, "Directory for the demo's files (default tspplay-demo)");
  c->add_option("--dataset", a->dataset, "Built-in dataset (default shock; see generate --list)");
  c->add_option("--dims", a->dims, "Grid size X,Y,Z or N (default: the dataset's)");
  c->add_option("--steps", a->steps, "Number of steps (default: the dataset's)");
  c->add_flag("--force", a->force, "Regenerate and rebuild even when the files exist");
  c->add_flag("--no-play", a->no_play, "Do not open the player afterwards, even with a display");
  c->callback([a] { run(*a); });
});

}  // namespace
}  // namespace tspcli

// tspplay render run.tsp --tf tf.json [...] -o frames/: headless frames and frames.json.
#include <array>
#include <utility>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/settings_options.h"
#include "jobs/calibration.h"
#include "jobs/movie.h"
#include "cli/progress_bar.h"
#include "cli/render_args.h"
#include "jobs/render_job.h"
#include "tsp/core/json_text.h"
#include "tsp/core/error.h"

namespace tspcli {
namespace {

// `render`'s options: the text options (cli/render_args.h) and the settings table's.
struct RenderCliArgs : RenderArgs {
  SettingsOptions settings;  ///< every knob of the settings table
  /// tspplay-mpi render's protocol (docs/mpi.md; hidden options): --mpi-check checks everything
  /// and prints what the driver needs as JSON; --mpi-part R/N with --mpi-dir DIR draws part R of
  /// N into DIR (no movie; --save-tf, by part 0, to DIR.tf.json).
  bool mpi_check = false;
  std::string mpi_part, mpi_dir;
};

/// The part R and part count N of --mpi-part R/N. Throws tsp::UsageError.
std::pair<int, int> parse_part(const std::string& text) {
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos)
    throw tsp::UsageError("--mpi-part " + text + ": expected R/N");
  const int parts = int(parse_integer(text.substr(slash + 1), "--mpi-part", 1, 1 << 20, "R/N"));
  const int part = int(parse_integer(text.substr(0, slash), "--mpi-part", 0, parts - 1, "R/N"));
  return {part, parts};
}

/// Applies --mpi-check, --mpi-part and --mpi-dir to o; returns whether this is a part (whose
/// tspplay-mpi rank 0 checked -o and makes the movie). Throws tsp::UsageError.
bool apply_mpi_protocol(const RenderCliArgs& a, tspgl::RenderJobOptions& o) {
  const bool part = !a.mpi_part.empty();
  if (part != !a.mpi_dir.empty()) throw tsp::UsageError("--mpi-part and --mpi-dir go together");
  if (part) {
    std::tie(o.part, o.parts) = parse_part(a.mpi_part);
    o.out_dir = a.mpi_dir;
    if (!a.save_tf.empty()) o.save_tf = o.part == 0 ? a.mpi_dir + ".tf.json" : "";
    o.movie.clear();  // rank 0 of tspplay-mpi encodes the whole movie
  }
  o.check_only = a.mpi_check;
  return part;
}

/// --mpi-check's answer on standard output: the outputs rank 0 of tspplay-mpi makes and the
/// inputs they must not be.
void print_check(const RenderCliArgs& a) {
  const nlohmann::json j = {{"out", a.out}, {"movie", a.movie}, {"fps", a.fps},
                            {"save_tf", a.save_tf}, {"passes", a.passes},
                            {"inputs", {a.file, a.tf, a.probe_tf, a.surface_mesh, a.surface_tf}}};
  std::printf("%s\n", tsp::json_text(j).c_str());
}

void run(const RenderCliArgs& a) {
  if (a.out.empty()) throw tsp::UsageError("-o: the output directory must not be empty");
  tspgl::RenderJobOptions o = render_job_options(a, a.settings.apply(), a.settings.given());
  apply_mpi_protocol(a, o);

  if (o.check_only) {
    tspgl::run_render_job(o);
    print_check(a);
    return;
  }
  ProgressBar bar;
  auto result = tspgl::run_render_job(
      o, [&bar](int done, int total) { bar.update("render", done, total); },
      [&bar](const std::string&, int done, int total) { bar.update("calibrate", done, total); });
  bar.finish();
  for (const std::string& w : result.warnings) std::fprintf(stderr, "tspplay: warning: %s\n", w.c_str());
  if (o.quality > 0)
    std::printf("quality mean dE <= %g: %s (calibration: every step within %.3g; %s)\n", o.quality,
                result.quality_options.c_str(), result.quality_calibrated_de,
                result.calibration_file.empty() ? "not cached" : result.calibration_file.c_str());
  const int last_pass = o.passes;
  double nr = 0, up = 0, rt = 0, nt = 0;
  int n = 0;
  for (const auto& f : result.frames) {
    if (f.pass != last_pass) continue;
    nr += f.report.class_percent[0];
    up += f.report.class_percent[1];
    rt += f.report.class_percent[2];
    nt += f.report.class_percent[3];
    ++n;
  }
  std::printf("rendered %zu frames (%d steps x %d passes) with %s\n", result.frames.size(), n,
              o.passes, result.renderer.c_str());
  std::printf("median frame %.2f ms (last pass), %.2f ms (all passes)\n",
              tspgl::median_frame_ms(result, last_pass), tspgl::median_frame_ms(result, 0));
  if (!o.baseline && n > 0)
    std::printf("voxels: %.1f%% not rendered, %.1f%% untextured, %.1f%% reused, %.1f%% new texture"
                " (last pass mean); metric %.1f ms\n",
                nr / n, up / n, rt / n, nt / n, result.metric_ms);
  if (!o.out_dir.empty()) std::printf("wrote %s/frames.json\n", o.out_dir.c_str());
  if (!a.movie.empty())
    std::printf("wrote %s (%zu frames, %d a second)\n", a.movie.c_str(),
                result.frames.size() / std::size_t(o.passes), a.fps);
}

const CommandRegistrar reg(30, [](CLI::App& app) {
  auto* c = app.add_subcommand("render", "Render steps headless (EGL or OSMesa: --gl) to PNGs and frames.json");
  auto a = std::make_shared<RenderCliArgs>();
  c->add_option("file", a->file, "The .tsp file")->required();
  c->add_option("--field", a->field, "A file with several fields: this one (default: the first)");
  c->add_option("--tf", a->tf,
                "Transfer function: a JSON file or preset:NAME (default preset:auto, built from "
                "the data's histogram)");
  c->add_option("-o,--output", a->out, "Directory for step_NNNN.png and frames.json")->required();
  c->add_option("--tf-range", a->tf_range,
                "Where the TF sits over the data: auto (presets and normalised [0,1] maps "
                "stretched over the data, other files as written), data, file, histogram (the "
                "1st to 99th percentile of the samples), step (the range of the first step drawn), "
                "visible (what this view and the probes show of it) or LO:HI");
  on_off_option(c, "--annotate", a->annotate,
              "Draw the outline box, an axes triad, a colour legend with ticks and the step (and "
              "time) into every frame (and so into --movie)");
  c->add_option("--movie", a->movie,
                "Also encode the frames into a movie: out.mp4 (H.264) or out.gif (needs ffmpeg)");
  c->add_option("--fps", a->fps, "Movie frames a second (default 8)");
  c->add_option("--steps", a->steps,
                "Steps A:B (inclusive), A:, A, or A:B:S for every S-th step (default: all)");
  c->add_option("--metric", a->metric, "scalar|reference|approximate|perceptual (default approximate)")
      ->check(CLI::IsMember({"scalar", "reference", "approximate", "perceptual"}));
  c->add_option("--cache", a->cache, "Texture cache on|off (default on)")
      ->check(CLI::IsMember({"on", "off"}));
  on_off_option(c, "--baseline", a->baseline, "Render without the TSP tree (the non-TSP reference)");
  c->add_option("--size", a->size, "Image size WxH (default 640x480)");
  c->add_option("--view", a->view, "Azimuth,elevation in degrees (default 30,20)");
  on_off_option(c, "--perspective", a->perspective, "Perspective projection (off: orthographic)");
  c->add_option("--proportions", a->proportions,
                "physical (default: the file's voxel spacing shapes the view) or samples (cubic "
                "voxels)");
  c->add_option("--probe", a->probes,
                "Clip probe in physical coordinates, repeatable: plane:A,B,C,D (keeps "
                "A*x+B*y+C*z <= D), sphere:X,Y,Z,R or box:X,Y,Z,HX,HY,HZ[,AX,AY,AZ] (half sizes, "
                "rotation in degrees); the volume outside their combination is not drawn");
  c->add_option("--probe-op", a->probe_op,
                "How the probes combine: intersect (default), union or subtract (the first "
                "minus the others)")
      ->check(CLI::IsMember({"intersect", "union", "subtract"}));
  c->add_option("--probe-surface", a->probe_surface,
                "on: draw the clip surface opaque, coloured by the data through --probe-tf and "
                "shaded by its normal; off (default): pure clipping")
      ->check(CLI::IsMember({"on", "off"}));
  c->add_option("--probe-motion", a->probe_motion,
                "DX,DY,DZ: every probe moves this far each frame (physical units; a plane along "
                "its normal), e.g. to sweep a slice through the data");
  c->add_option("--probe-tf", a->probe_tf,
                "Colours of the clip surface: a TF file or preset:NAME (default: --tf's)");
  c->add_option("--surface-mesh", a->surface_mesh,
                "The mesh series the file was built from (any build input: .vtu, .pvd, "
                ".vtm.series, 'can_%d.hdf', ...), whose boundary --surface draws");
  c->add_option("--surface-field", a->surface_field,
                "The field the surface shows (any of the mesh's, e.g. another than the "
                "volume's; default: the file's field)");
  c->add_option("--surface-tf", a->surface_tf,
                "Colours of the surface: a TF file or preset:NAME (default preset:cool-to-warm "
                "over the surface's values at the first step that holds more than one)");
  c->add_option("--surface-target-ms", a->surface_target_ms,
                "Hold the surface pass at this many ms: the minimum splat size adapts frame by "
                "frame, from --surface-px (TetSplat's frame-rate knob; frames.json records it)");
  c->add_option("--scale", a->scale,
                "SX,SY,SZ: stretch each axis by this factor (e.g. 1,1,20 exaggerates height)");
  c->add_option("--passes", a->passes, "Play the steps this many times (default 1)");
  c->add_option("--gl", a->gl,
                "Which GL draws: auto (EGL on a GPU when one is found, else OSMesa), egl (EGL, on "
                "Mesa's software device where there is no GPU) or osmesa; a request EGL cannot "
                "serve falls back to OSMesa with a warning (frames.json: context)");
  c->add_option("--gpu", a->gpu,
                "EGL device index to draw on (default: TSPPLAY_EGL_DEVICE, else the first GPU)");
  c->add_option("--texture-budget", a->texture_budget_mb, "Texture cache budget in MiB (default 512)");
  c->add_option("--ram-budget", a->ram_budget_mb,
                "Bricks held in RAM, MiB (default 1024): a file larger than RAM streams through "
                "it (frames.json records ram_mib and rss_mib per frame)");
  c->add_option("--quality", a->quality,
                "Mean dE target against the full-quality picture: picks the fastest calibrated "
                "compositing, spacing, tolerances and pre-integration (calibrates once, cached)")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            // (0 is how the job reads "not asked", so a given 0 is refused here, not ignored.)
            char* end = nullptr;
            const double de = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != 0 || !(de > 0 && de <= tspgl::kMaxQualityDe))
              return "expected a mean dE in (0, " + std::to_string(int(tspgl::kMaxQualityDe)) +
                     "], got " + text;
            return "";
          },
          "DE"));
  c->add_option("--save-tf", a->save_tf,
                "Also write the transfer function used (a preset resolved over the data's range) "
                "as JSON, e.g. for bench/vtk_reference.py");
  c->add_option("--lod", a->lod,
                "Spatial level of detail: off (full resolution: the default, so frames are "
                "reproducible; play's default is on, for interaction), K (level K everywhere; 0 = "
                "full), auto (the adaptive cut; default with --target-fps) or splat:PX (every node drawn "
                "as one splat of its mean colour and opacity, split while its children project to "
                "PX pixels or more)");
  c->add_option("--lod-fallback", a->lod_fallback,
                "--lod auto, when even the coarsest cut misses the target: scale (a smaller "
                "render target, default) or splats (a splat cut whose minimum size adapts)");
  c->add_option("--target-fps", a->target_fps,
                "Frames per second --lod auto holds by adapting the cut (as play's --target-fps)");
  c->add_option("--target-ms", a->target_ms,
                "The same target as a frame time in ms (kept for older scripts)")
      ->group("");  // hidden: one unit per concept in --help
  c->add_option("--orbit", a->orbit, "Advance the azimuth this many degrees every frame");
  c->add_option("--split-limit", a->split_limit,
                "--lod auto: most node splits per frame (default 8)");
  c->add_option("--lod-filter", a->lod_filter,
                "How the cut is chosen: error (the error-driven cut of --lod auto), or LaMar's "
                "selection filters distance[:K] (a tile drawn when the eye is more than K times "
                "its diagonal away) and fov[:K] (drawn when it subtends less than half the field "
                "of view over K; outside the view: not refined); default error");
  c->add_option("--eye", a->eye,
                "Place the eye at X,Y,Z in voxels (inside the volume or out), looking along "
                "--view's direction; implies --perspective");
  c->add_option("--focus", a->focus,
                "--lod auto: centre of attention X,Y,Z in voxels (default the volume centre)");
  c->add_option("--calibration-dir", a->calibration_dir,
                "Where --quality caches calibrations (default $TSPPLAY_CACHE_DIR, "
                "$XDG_CACHE_HOME/tspplay or ~/.cache/tspplay; - for none)");
  c->add_flag("--mpi-check", a->mpi_check)->group("");  // tspplay-mpi render's protocol
  c->add_option("--mpi-part", a->mpi_part)->group("");
  c->add_option("--mpi-dir", a->mpi_dir)->group("");
  a->settings.add_to(c);
  set_groups(c, {{"Input/output", {"--field", "--tf", "--output", "--tf-range", "--annotate",
                                   "--movie", "--fps", "--steps", "--passes", "--save-tf"}},
                 {"Camera", {"--size", "--view", "--perspective", "--eye", "--proportions", "--scale",
                             "--orbit"}},
                 {"Quality", {"--metric", "--quality", "--calibration-dir"}},
                 {"LOD", {"--lod", "--lod-filter", "--lod-fallback", "--target-fps", "--split-limit",
                          "--focus"}},
                 {"Probes", {"--probe", "--probe-op", "--probe-surface", "--probe-motion",
                             "--probe-tf"}},
                 {"Surface", {"--surface-mesh", "--surface-field", "--surface-tf",
                              "--surface-target-ms"}},
                 {"Memory", {"--texture-budget", "--ram-budget"}},
                 {"GL", {"--gl", "--gpu"}},
                 {"Diagnostics", {"--baseline", "--cache"}}});
  c->callback([a] { run(*a); });
});

}  // namespace
}  // namespace tspcli

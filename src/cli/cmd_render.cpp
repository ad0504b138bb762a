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
#include "cli/session_options.h"
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
  // The session options, with render's defaults: one table (session_options.h).
  add_session_options(c, SessionCommand::render, *a);
  c->add_option("-o,--output", a->out, "Directory for step_NNNN.png and frames.json")->required();
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
  on_off_option(c, "--perspective", a->perspective, "Perspective projection (off: orthographic)");
  c->add_option("--probe-motion", a->probe_motion,
                "DX,DY,DZ: every probe moves this far each frame (physical units; a plane along "
                "its normal), e.g. to sweep a slice through the data");
  c->add_option("--probe-tf", a->probe_tf,
                "Colours of the clip surface: a TF file or preset:NAME (default: --tf's)");
  c->add_option("--surface-target-ms", a->surface_target_ms,
                "Hold the surface pass at this many ms: the minimum splat size adapts frame by "
                "frame, from --surface-px (TetSplat's frame-rate knob; frames.json records it)");
  c->add_option("--passes", a->passes, "Play the steps this many times (default 1)");
  c->add_option("--save-tf", a->save_tf,
                "Also write the transfer function used (a preset resolved over the data's range) "
                "as JSON, e.g. for bench/vtk_reference.py");
  c->add_option("--target-ms", a->target_ms,
                "The same target as a frame time in ms (kept for older scripts)")
      ->group("");  // hidden: one unit per concept in --help
  c->add_option("--orbit", a->orbit, "Advance the azimuth this many degrees every frame");
  c->add_option("--split-limit", a->split_limit,
                "--lod auto: most node splits per frame (default 8)");
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
  // (0 is how the job reads "not asked", so a given 0 is refused here, not ignored.)
  c->get_option("--quality")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            char* end = nullptr;
            const double de = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != 0 || !(de > 0 && de <= tspgl::kMaxQualityDe))
              return "expected a mean dE in (0, " + std::to_string(int(tspgl::kMaxQualityDe)) +
                     "], got " + text;
            return "";
          },
          "DE"));
  a->settings.add_to(c);
  // (The session options are in their table's groups: session_options.h.)
  set_groups(c, {{"Input/output",
                  {"--output", "--annotate", "--movie", "--fps", "--steps", "--passes", "--save-tf"}},
                 {"Camera", {"--perspective", "--eye", "--orbit"}},
                 {"Quality", {"--metric", "--calibration-dir"}},
                 {"LOD", {"--split-limit", "--focus"}},
                 {"Probes", {"--probe-motion", "--probe-tf"}},
                 {"Surface", {"--surface-target-ms"}},
                 {"Diagnostics", {"--baseline", "--cache"}}});
  c->callback([a] { run(*a); });
});

}  // namespace
}  // namespace tspcli

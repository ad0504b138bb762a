// tspplay play run.tsp [--tf tf.json] [--step K] [--screenshot out.png] [--script FILE]
// [--size WxH]: the window player (docs/player.md).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/args.h"
#include "cli/build_runner.h"
#include "cli/commands.h"
#include "cli/input_options.h"
#include "cli/session_options.h"
#include "cli/settings_options.h"
#include "jobs/play_input.h"
#include "player/controls.h"
#include "player/player.h"
#include "tsp/build/build.h"
#include "tsp/core/error.h"
#include "tsp/core/temp_output.h"
#include "tsp/lod/lod_controller.h"

namespace tspcli {
namespace {

struct PlayArgs {
  tspplayer::PlayerOptions options;
  SessionArgs session = session_defaults(SessionCommand::play);  // the shared options' values
  std::string cache_dir;
  SettingsOptions settings{tspplayer::default_player_settings()};
  std::string playback = "quality";
  InputArgs in;  // how an input that is not a .tsp is read (as for build)
};

// The session options (s) into the player's: checked as render checks them.
void apply_session(const SessionArgs& s, tspplayer::PlayerOptions& o) {
  const auto x = s.size.find('x');
  if (x == std::string::npos) throw tsp::UsageError("--size '" + s.size + "': expected WxH");
  o.width = int(parse_integer(s.size.substr(0, x), "--size", 1, 8192, "WxH, 1..8192"));
  o.height = int(parse_integer(s.size.substr(x + 1), "--size", 1, 8192, "WxH, 1..8192"));
  o.tf = s.tf;
  o.tf_range = s.tf_range;
  if (s.proportions != "physical" && s.proportions != "samples")
    throw tsp::UsageError("--proportions '" + s.proportions + "': expected physical or samples");
  o.physical_proportions = s.proportions == "physical";
  if (!s.scale.empty())
    o.scale = parse_triple(s.scale, "--scale", "SX,SY,SZ, factors on the voxel spacing");
  o.probes = s.probes;
  o.probe_op = s.probe_op;
  o.probe_surface = s.probe_surface == "on";
  o.surface_mesh = s.surface_mesh;
  o.surface_field = s.surface_field;
  o.surface_tf = s.surface_tf;
  const std::string lod = lod_word(s.lod);
  if (lod != "auto" && lod != "off")
    throw tsp::UsageError("--lod " + s.lod + ": play holds a frame rate, so its cut is auto (on) "
                          "or off; a fixed level K or splat:PX is render's");
  o.lod = lod == "auto";
  o.splat_fallback =
      tsp::parse_lod_fallback(s.lod_fallback, "--lod-fallback") == tsp::LodFallback::splats;
  o.lod_filter = s.lod_filter;
  o.target_fps = s.target_fps;
  o.quality = s.quality;
  o.ram_budget_mb = s.ram_budget_mb;
  o.texture_budget_mb = s.texture_budget_mb;
}

void run(PlayArgs a) {
  apply_session(a.session, a.options);
  a.options.cache_dir = a.cache_dir;
  a.options.input.source = source_options(a.in, "");
  a.options.input.voxelize = voxelize_options(a.in, 0);
  a.options.input.key = input_key(a.in);
  a.options.input.adaptive = octree_error(a.in, a.options.input.octree);
  // File > Open's options line: parsed by the same options, starting from the command line's.
  a.options.parse_input_options = [base = a.in](const std::string& line) {
    CLI::App parser("File > Open build options");
    InputArgs in = base;
    add_input_options(&parser, in);
    try {
      parser.parse(line, false);
    } catch (const CLI::CallForHelp&) {  // (CLI11's what() would say "caught in your main")
      throw tsp::UsageError("build options '" + line +
                            "': --help asks for help, not a build; the options an input "
                            "opened here takes are:\n" + parser.help());
    } catch (const CLI::ParseError& e) {
      throw tsp::UsageError("build options '" + line + "': " + e.what());
    }
    tspgl::PlayInputOptions o;
    o.source = source_options(in, "");
    o.voxelize = voxelize_options(in, 0);
    o.key = input_key(in);
    o.adaptive = octree_error(in, o.octree);
    return o;
  };
  tspgl::PlayBuildHooks hooks;
  hooks.say = [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  hooks.build = [](tsp::VolumeSource& source, const std::string& out, tsp::BuildOptions o) {
    tsp::BuildReport r = build_with_progress(source, out, o);
    print_build_summary(out, r);
    return r;
  };
  hooks.build_adaptive = [](tsp::MeshSource& mesh, const std::string& out, tsp::AdaptiveOptions o) {
    print_adaptive_summary(out, build_adaptive_with_progress(mesh, out, o));
  };
  hooks.build_fields = [](const tsp::FieldSourceFn& open_field,
                          const std::vector<std::string>& fields, const std::string& out,
                          tsp::BuildOptions o) {
    const std::vector<tsp::BuildReport> r = build_fields_with_progress(open_field, fields, out, o);
    print_build_summary(out, r.front());
  };
  // The played file, its TF and script are never replaced by a screenshot, stats or recording.
  const tsp::InputGuard inputs(
      {a.options.tsp_path, a.options.tf, a.options.script, a.options.session});
  if (!a.options.screenshot.empty()) tsp::check_output_path(a.options.screenshot);
  const bool tsp = tspgl::is_tsp_file(a.options.tsp_path);
  // --surface boundary on a mesh input: its own boundary.
  if (a.options.settings.surface && a.options.surface_mesh.empty() && !tsp)
    a.options.surface_mesh = a.options.tsp_path;
  if (a.options.settings.surface && a.options.surface_mesh.empty())
    throw tsp::UsageError("--surface boundary needs a mesh: play a mesh input, or give "
                          "--surface-mesh (the mesh series the file was built from)");
  if (a.options.settings.surface && a.options.settings.compositing != tspgl::Compositing::rays)
    throw tsp::UsageError("--surface boundary is drawn with --compositing rays");
  tspgl::PlayInputOptions input = a.options.input;
  input.field = a.session.field;
  a.options.input_path = a.options.tsp_path;  // (File > Open starts in its folder)
  a.options.tsp_path = tspgl::prepare_play_input(a.options.tsp_path, input, a.cache_dir, hooks);
  // A .tsp: the field shown first; an input: the one built.
  a.options.field = tsp ? a.session.field : "";
  tspplayer::run_player(a.options);
}

const CommandRegistrar reg(35, [](CLI::App& app) {
  auto* c = app.add_subcommand("play", "Play a .tsp file (or any input, built first) in a window "
                                       "(GLFW + Dear ImGui)");
  auto a = std::make_shared<PlayArgs>();
  c->add_option("file", a->options.tsp_path,
                "The .tsp file, or any input build reads (built into the cache folder first, "
                "reused while unchanged)")
      ->required();
  // The session options, with play's defaults: one table (session_options.h).
  add_session_options(c, SessionCommand::play, a->session);
  add_input_options(c, a->in);
  c->add_option("--cache-dir", a->cache_dir,
                "Raw input: the cache folder (default $TSPPLAY_CACHE_DIR, $XDG_CACHE_HOME/tspplay "
                "or ~/.cache/tspplay; builds go to its builds/)");
  c->add_option("--step", a->options.step, "Step shown first (default 0)");
  c->add_option("--screenshot", a->options.screenshot,
                "Save the first complete frame (volume only) as PNG and exit");
  c->add_option("--script", a->options.script, "Run a script of player actions (docs/player.md)");
  c->add_option("--session", a->options.session,
                "Start from a session saved with File > Save session... or the script's "
                "save-session (TF, view, probes, surface, axis scale, speed, panels; options "
                "named here win). Default: the input's own last session, kept per input and "
                "field in the cache folder's sessions/ when the window quits");
  c->add_flag("--no-session", a->options.no_session,
              "Start with the defaults: neither restore nor keep the input's session");
  c->add_option("--frame-delay-ms", a->options.frame_delay_ms,
                "Sleep this long every frame: a slow machine, for tests (default 0)");
  c->add_flag("--trace", a->options.trace,
              "Print one line per applied change (step, transfer function, tolerances, metric, "
              "play/pause, LOD) and per saved screenshot");
  c->add_option("--speed", a->options.speed,
                "Playback speed, steps per second, 0.25 to 60 (default: the series in about 4 s, "
                "at most 24, a movie's rate). Steps are shown in order, slower if frames are "
                "slow, unless the script or panel picks skip steps");
  c->add_option("--playback", a->playback,
                "With --quality, what gives while playing when no rung both fits the speed and "
                "keeps the target: quality (steps show later; default) or rate (a coarser rung)")
      ->check(CLI::IsMember({"quality", "rate"}));
  std::string keys = "\nControls (also F1 or ? in the player):\n";
  for (const tspplayer::Control& k : tspplayer::kControls)
    keys += "  " + std::string(k.input) +
            std::string(std::size_t(std::max(2, 42 - int(std::string(k.input).size()))), ' ') +
            k.action + "\n";
  c->footer(keys);
  a->settings.add_to(c);
  // (The session options are in their table's groups: session_options.h.)
  set_groups(c, {{"Input/output", {"--cache-dir", "--step", "--screenshot", "--script", "--session",
                                   "--no-session"}},
                 {"Input to build (not a .tsp; as for build)",
                  {"--raw-dims", "--raw-type", "--big-endian", "--allow-external", "--resolution",
                   "--voxel-size", "--cell-data", "--voxelizer", "--antialias", "--jitter", "--hex",
                   "--vertical-levels"}},
                 {"Playback", {"--speed", "--playback"}},
                 {"Diagnostics", {"--trace", "--frame-delay-ms"}}});
  c->callback([a, c] {
    // What the command line names wins over a restored session.
    for (const char* o : {"--field", "--tf", "--tf-range", "--step", "--speed", "--scale", "--probe",
                          "--probe-op", "--probe-surface", "--surface"})
      if (c->count(o) > 0) a->options.given.push_back(o);
    a->options.settings = a->settings.apply();
    a->options.keep_quality = a->playback == "quality";
    run(*a);
  });
});

}  // namespace
}  // namespace tspcli

// tspplay play run.tsp [--tf tf.json] [--step K] [--screenshot out.png] [--script FILE]
// [--size WxH]: the window player (docs/player.md).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/args.h"
#include "cli/build_runner.h"
#include "cli/commands.h"
#include "jobs/calibration.h"
#include "player/controls.h"
#include "player/player.h"
#include "tsp/build/build.h"
#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/hdf5/hdf5_lock.h"
#include "tsp/voxelize/open_input.h"

namespace tspcli {
namespace {

namespace fs = std::filesystem;

struct PlayArgs {
  tspplayer::PlayerOptions options;
  std::string size = "960x720";
  std::string lod = "on";
  std::string field, cache_dir;
};

// True when path is a .tsp file (an HDF5 file whose root says format = "tspplay").
bool is_tsp_file(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;
  std::lock_guard lock(tsp::hdf5_mutex());
  tsp::h5::silence_errors();
  if (H5Fis_hdf5(path.c_str()) <= 0) return false;
  tsp::h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  return f && H5Aexists(f.get(), "format") > 0;
}

// FNV-1a of text, for cache names.
std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

// A raw input (anything but a .tsp) built into the cache folder, reused while the input and
// the field are unchanged: the cache name hashes the input's absolute path, size, modification
// time and field. Returns the .tsp to play. Throws what opening or building the input throws.
std::string built_for_play(const std::string& input, const std::string& field,
                           const std::string& cache_dir) {
  std::error_code ec;
  const fs::path abs = fs::absolute(input, ec);
  std::string key = abs.string() + "|" + field;
  if (fs::is_regular_file(input, ec))  // (a pattern names no one file: its path alone)
    key += "|" + std::to_string(fs::file_size(input, ec)) + "|" +
           std::to_string(fs::last_write_time(input, ec).time_since_epoch().count());
  const std::string dir = cache_dir.empty() ? tspgl::default_calibration_dir() : cache_dir;
  if (dir.empty())
    throw tsp::UsageError(input + " is not a .tsp file and there is no cache folder to build it "
                          "into (set HOME, XDG_CACHE_HOME or --cache-dir)");
  const fs::path builds = fs::path(dir) / "builds";
  fs::create_directories(builds, ec);
  if (ec) throw tsp::IoError(builds.string() + ": cannot create the build cache: " + ec.message());
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a(key)));
  const fs::path out = builds / (abs.filename().string() + "-" + hash + ".tsp");
  if (is_tsp_file(out.string())) {
    std::printf("play: %s is not a .tsp file; playing %s, built from it earlier\n", input.c_str(),
                out.string().c_str());
    return out.string();
  }
  std::printf("play: %s is not a .tsp file; building it into %s (reused next time)\n",
              input.c_str(), out.string().c_str());
  std::fflush(stdout);
  tsp::SourceOptions so;
  so.field = field;
  auto source = tsp::open_input(input, so, tsp::VoxelizeOptions{});
  tsp::BuildOptions bo;
  bo.field_name = field;
  bo.brick_size = tsp::default_brick_size(source->dims());
  tsp::BuildReport r = build_with_progress(*source, out.string(), bo);
  print_build_summary(out.string(), r);
  return out.string();
}

void run(PlayArgs a) {
  auto x = a.size.find('x');
  if (x == std::string::npos) throw tsp::UsageError("--size '" + a.size + "': expected WxH");
  a.options.width = int(parse_integer(a.size.substr(0, x), "--size", 1, 8192, "WxH, 1..8192"));
  a.options.height = int(parse_integer(a.size.substr(x + 1), "--size", 1, 8192, "WxH, 1..8192"));
  if (!is_tsp_file(a.options.tsp_path))
    a.options.tsp_path = built_for_play(a.options.tsp_path, a.field, a.cache_dir);
  else if (!a.field.empty())
    throw tsp::UsageError("--field " + a.field + ": " + a.options.tsp_path +
                          " is a .tsp file (its field was chosen when it was built)");
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
  c->add_option("--field", a->field, "Raw input: the field to build (as for build --field)");
  c->add_option("--cache-dir", a->cache_dir,
                "Raw input: the cache folder (default $TSPPLAY_CACHE_DIR, $XDG_CACHE_HOME/tspplay "
                "or ~/.cache/tspplay; builds go to its builds/)");
  c->add_option("--tf", a->options.tf,
                "Transfer function: a JSON file or preset:NAME (default preset:sparse)");
  c->add_option("--tf-range", a->options.tf_range,
                "Where the TF sits over the data: auto, data, file or LO:HI (as for render)");
  c->add_option("--step", a->options.step, "Step shown first (default 0)");
  c->add_option("--screenshot", a->options.screenshot,
                "Save the first complete frame (volume only) as PNG and exit");
  c->add_option("--script", a->options.script, "Run a script of player actions (docs/player.md)");
  c->add_option("--frame-delay-ms", a->options.frame_delay_ms,
                "Sleep this long every frame: a slow machine, for tests (default 0)");
  c->add_flag("--trace", a->options.trace,
              "Print one line per applied change (step, transfer function, tolerances, metric, "
              "play/pause, LOD) and per saved screenshot");
  c->add_option("--size", a->size, "Window size WxH (default 960x720)");
  c->add_option("--upload-budget", a->options.upload_budget_mb,
                "Texture MiB uploaded per frame; the rest follows in later frames (default 16, "
                "0: no limit)");
  c->add_option("--lod", a->lod, "Level of detail: on (hold --target-fps while interacting, full "
                                 "quality when idle) or off (default on)")
      ->check(CLI::IsMember({"on", "off"}));
  c->add_option("--target-fps", a->options.target_fps,
                "Frames per second the LOD cut holds while interacting (default 30)");
  std::string keys = "\nControls (also F1 or ? in the player):\n";
  for (const tspplayer::Control& k : tspplayer::kControls)
    keys += "  " + std::string(k.input) +
            std::string(std::size_t(std::max(2, 42 - int(std::string(k.input).size()))), ' ') +
            k.action + "\n";
  c->footer(keys);
  c->callback([a] {
    a->options.lod = a->lod == "on";
    run(*a);
  });
});

}  // namespace
}  // namespace tspcli

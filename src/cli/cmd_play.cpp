// tspplay play run.tsp [--tf tf.json] [--step K] [--screenshot out.png] [--script FILE]
// [--size WxH]: the window player (docs/player.md).
#include <memory>
#include <string>

#include "cli/args.h"
#include "cli/commands.h"
#include "player/player.h"
#include "tsp/core/error.h"

namespace tspcli {
namespace {

struct PlayArgs {
  tspplayer::PlayerOptions options;
  std::string size = "960x720";
  std::string lod = "on";
};

void run(PlayArgs a) {
  auto x = a.size.find('x');
  if (x == std::string::npos) throw tsp::UsageError("--size '" + a.size + "': expected WxH");
  a.options.width = int(parse_integer(a.size.substr(0, x), "--size", 1, 8192, "WxH, 1..8192"));
  a.options.height = int(parse_integer(a.size.substr(x + 1), "--size", 1, 8192, "WxH, 1..8192"));
  tspplayer::run_player(a.options);
}

const CommandRegistrar reg(35, [](CLI::App& app) {
  auto* c = app.add_subcommand("play", "Play a .tsp file in a window (GLFW + Dear ImGui)");
  auto a = std::make_shared<PlayArgs>();
  c->add_option("file", a->options.tsp_path, "The .tsp file")->required();
  c->add_option("--tf", a->options.tf,
                "Transfer function: a JSON file or preset:NAME (default preset:sparse)");
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
  c->callback([a] {
    a->options.lod = a->lod == "on";
    run(*a);
  });
});

}  // namespace
}  // namespace tspcli

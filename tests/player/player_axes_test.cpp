// The view's axis scale (issue 47 item 8): a flat domain opens stretched in height and says so
// ("z × 10" in stats and over the picture); the axis-scale field applies a typed value on Enter
// and Escape cancels the edit only.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/paths.h"
#include "support/player_run.h"

namespace {

namespace fs = std::filesystem;
using namespace tsptest::player;
using tsptest::q;
using tsptest::run_tspplay;

// The axis scale and its name in the stats of `play FILE ARGS` after the first frame.
nlohmann::json opened(const fs::path& tsp, const std::string& args, const fs::path& dir) {
  const fs::path stats = dir / "s.json";
  fs::remove(stats);
  const fs::path script = write_script("stats " + stats.string() + "\nquit\n");
  const auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " + q(script) + args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return read_json(stats);
}

// 24 × 24 × 8 samples 1000 × 1000 × 100 m apart: 23 km wide, 700 m tall. A third of 32.9 is 11:
// the view opens at z × 10 (the round number nearest). --scale or sample proportions keep theirs.
TEST(Player, FlatDomainOpensWithANamedVerticalExaggeration) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), h5 = dir / "flat.h5", tsp = dir / "flat.tsp";
  ASSERT_EQ(run_tspplay("generate shock -o " + q(h5) + " --dims 24,24,8 --steps 2").exit_code, 0);
  ASSERT_EQ(run_tspplay("build " + q(h5) + " --spacing 1000,1000,100 -o " + q(tsp)).exit_code, 0);
  nlohmann::json j = opened(tsp, "", dir);
  EXPECT_EQ(j["axis_scale"], nlohmann::json({1.0, 1.0, 10.0}));
  EXPECT_EQ(j["exaggeration"], "z × 10");
  j = opened(tsp, " --scale 1,1,2", dir);
  EXPECT_EQ(j["axis_scale"], nlohmann::json({1.0, 1.0, 2.0}));
  EXPECT_EQ(j["exaggeration"], "z × 2");
  j = opened(tsp, " --proportions samples", dir);
  EXPECT_EQ(j["axis_scale"], nlohmann::json({1.0, 1.0, 1.0}));
  EXPECT_EQ(j["exaggeration"], "");
  // A cube-ish domain opens as it is.
  j = opened(make_tsp(), "", dir);
  EXPECT_EQ(j["axis_scale"], nlohmann::json({1.0, 1.0, 1.0}));
  EXPECT_EQ(j["exaggeration"], "");
}

// Real X events (xdotool): Ctrl+click the z field, type 7, Escape: nothing applied (before, the
// view took each keystroke and Escape reverted it). Again with Enter: z × 7 applied.
// Each key or click is a handshake: the script goes on once the window has taken it (Escape and
// Enter are pressed and released in separate frames).
TEST(Player, AxisScaleFieldAppliesOnEnterAndEscapeCancelsTheEdit) {
  TSPTEST_REQUIRE_X_EVENTS();
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const fs::path out = dir / "axes.out", stats = dir / "axes.json";
  // The stages of a Ctrl+click and 7 typed (their handshakes end in N: 1 or 2), then a key held
  // and released.
  const char* const stages[] = {"hover", "ctrl", "click", "unctrl", "typed"};
  std::string lines = "wait-frames 4\nsignal " + (dir / "ready").string() + "\n";
  for (const char* n : {"1", "2"}) {
    for (const char* stage : stages) lines += taken(dir, stage + std::string(n));
    lines += taken(dir, "keydown" + std::string(n)) + taken(dir, "keyup" + std::string(n));
  }
  const fs::path script = write_script(lines + "stats " + stats.string() + "\nquit\n");
  auto ctrl_click = [](const std::string& n) {
    return "xdotool mousemove --window \"$win\" $cx $cy; handshake hover" + n + "\n"
           "xdotool keydown ctrl; handshake ctrl" + n + "; xdotool click 1; handshake click" + n +
           "\nxdotool keyup ctrl; handshake unctrl" + n + "\n"
           "xdotool type --window \"$win\" 7; handshake typed" + n + "\n";
  };
  auto tap = [](const std::string& key, const std::string& n) {
    return "xdotool keydown --window \"$win\" " + key + "; handshake keydown" + n +
           "; xdotool keyup --window \"$win\" " + key + "; handshake keyup" + n + "\n";
  };
  const std::string cmd =
      log_waits(out) + handshakes(dir) + "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) +
      " --size 800x800 --trace --script " + q(script) + " > " + q(out) + " 2>&1 &\n" +
      "until_file " + q(dir / "ready") + "\n"
      "read x y w h <<< $(grep 'axis scale field' " + q(out) + " | tail -1 | cut -d' ' -f5-8)\n"
      "win=$(timeout 20 xdotool search --sync --name " + q("tspplay - " + tsp.string()) +
      " | head -1)\n"
      "cx=$((x + w / 2)); cy=$((y + h / 2))\n" + ctrl_click("1") + tap("Escape", "1") +
      "grep -c 'trace: axis scale [0-9]' " + q(out) + " > " + q(dir / "escaped.count") + "\n" +
      ctrl_click("2") + tap("Return", "2") + "wait)\n";
  ASSERT_EQ(run_bash(dir / "axes.sh", cmd), 0);
  const std::string log = read_text(out);
  // Nothing applied by the time Escape was pressed; 7 after Enter.
  EXPECT_EQ(read_text(dir / "escaped.count"), "0\n") << log;
  EXPECT_NE(log.find("trace: axis scale 1,1,7\n"), std::string::npos) << log;
  // One change, one trace line (issue 47 walk 6: Enter printed it twice).
  EXPECT_EQ(log.find("trace: axis scale 1,1,7\n"), log.rfind("trace: axis scale 1,1,7\n")) << log;
  EXPECT_EQ(log.find("trace: axis scale 1,1,1"), std::string::npos) << log;
  EXPECT_EQ(read_json(stats)["axis_scale"], nlohmann::json({1.0, 1.0, 7.0})) << log;
}

}  // namespace

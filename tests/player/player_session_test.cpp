// tspplay play's sessions (issue 47 item 4): what one window shows is restored by the next on the
// same input, a bad or foreign state file is ignored with a message naming it, a shared session
// opens with --session (a bad one is an error naming it); and File > Open's path field (Ctrl+O,
// Ctrl+A) under real X key events (issue 47 item 6). (Helpers: support/player_run.h.)
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/paths.h"
#include "support/player_run.h"

namespace {

namespace fs = std::filesystem;
using tsptest::q;
using tsptest::run_tspplay;
using namespace tsptest::player;

// The settings a session keeps, as `stats` writes them.
nlohmann::json kept(const nlohmann::json& s) {
  return {{"tf", s["tf"]},           {"tf_domain", s["tf_domain"]},
          {"tf_points", s["tf_points"]}, {"camera", s["camera"]},
          {"scale", s["scale"]},     {"speed", s["playback"]["speed"]},
          {"step", s["step"]},       {"probes", s["probes"]},
          {"probe_op", s["probe_op"]}, {"panels", s["panels"]},
          {"every_step", s["every_step"]}};
}

// Changes by script what a session keeps (TF, camera, speed, probe, axis scale, step, panels).
constexpr const char* kChanges =
    "tf preset:filled\ntf-range 0.2:0.7\nview 75 -30\nzoom 1.7\nprojection persp\nspeed 3.5\n"
    "probe sphere:15,14,13,6\nprobe-op union\nscale 1,1,2.5\nstep 2\nevery-step off\n"
    "panels off\n";

struct Played {
  tsptest::RunResult run;
  nlohmann::json stats;
};

Played play(const fs::path& tsp, const std::string& extra, const std::string& actions,
            const fs::path& stats, const std::string& size = kSize) {
  Played p;
  p.run = run_tspplay("play " + q(tsp) + " --size " + size + extra + " --script " +
                      q(write_script(actions + "stats " + stats.string() + "\nquit\n")));
  if (p.run.exit_code == 0 && fs::exists(stats)) p.stats = read_json(stats);
  return p;
}

TEST(Player, SessionIsRestoredWhenTheSameInputIsPlayedAgain) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string cache = " --cache-dir " + q(dir / "cache");
  const Played a = play(tsp, cache, kChanges, dir / "a.json");
  ASSERT_EQ(a.run.exit_code, 0) << a.run.err;
  EXPECT_FALSE(a.stats["session"]["restored"].get<bool>());  // a fresh cache folder
  const std::string entry = a.stats["session"]["file"].get<std::string>();
  EXPECT_EQ(fs::path(entry).parent_path(), dir / "cache" / "sessions");
  ASSERT_TRUE(fs::is_regular_file(entry));  // written when the window quit
  EXPECT_EQ(a.stats["tf"], "filled");
  EXPECT_EQ(a.stats["scale"], nlohmann::json({1, 1, 2.5}));

  // The next window on the same input: every setting back, and it says where from.
  const Played b = play(tsp, cache, "", dir / "b.json");
  ASSERT_EQ(b.run.exit_code, 0) << b.run.err;
  EXPECT_TRUE(b.stats["session"]["restored"].get<bool>()) << b.stats["session"];
  EXPECT_EQ(b.stats["session"]["from"], entry);
  EXPECT_EQ(kept(b.stats), kept(a.stats));
  EXPECT_NE(b.stats["status"].get<std::string>().find("restored session from " + entry),
            std::string::npos) << b.stats["status"];

  // What play's command line names wins; the rest is restored.
  const Played c = play(tsp, cache + " --speed 2", "", dir / "c.json");
  ASSERT_EQ(c.run.exit_code, 0) << c.run.err;
  EXPECT_EQ(c.stats["playback"]["speed"], 2.0);
  EXPECT_EQ(c.stats["camera"], a.stats["camera"]);

  // --no-session starts with the defaults (and keeps nothing: the next window restores again).
  const Played d = play(tsp, cache + " --no-session", "", dir / "d.json");
  ASSERT_EQ(d.run.exit_code, 0) << d.run.err;
  EXPECT_FALSE(d.stats["session"]["restored"].get<bool>());
  EXPECT_EQ(d.stats["tf"], "auto");
  EXPECT_EQ(d.stats["scale"], nlohmann::json({1, 1, 1}));
  EXPECT_EQ(d.stats["probes"], nlohmann::json::array());
  EXPECT_NE(d.stats["camera"], a.stats["camera"]);
  EXPECT_TRUE(d.stats["panels"].get<bool>());
  const Played e = play(tsp, cache, "", dir / "e.json");
  ASSERT_EQ(e.run.exit_code, 0) << e.run.err;
  EXPECT_EQ(e.stats["camera"], a.stats["camera"]);
  EXPECT_EQ(e.stats["playback"]["speed"], 2.0);  // (c quit with speed 2)
}

TEST(Player, BadOrForeignSessionFileIsIgnoredWithAMessage) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string cache = " --cache-dir " + q(dir / "cache");
  const Played a = play(tsp, cache, "speed 3.5\nview 75 -30\n", dir / "a.json");
  ASSERT_EQ(a.run.exit_code, 0) << a.run.err;
  const std::string entry = a.stats["session"]["file"].get<std::string>();
  for (const std::string& bad : {std::string("{ not json"), std::string(R"({"version": 99})")}) {
    std::ofstream(entry) << bad;
    // The window reads it, says what is wrong with which file, and opens with the defaults;
    // the file stays as it was while the window runs.
    const Played b = play(tsp, cache, "", dir / "b.json");
    ASSERT_EQ(b.run.exit_code, 0) << b.run.err;
    EXPECT_FALSE(b.stats["session"]["restored"].get<bool>());
    const std::string note = b.stats["session"]["ignored"].get<std::string>();
    EXPECT_NE(note.find(entry), std::string::npos) << note;
    EXPECT_NE(note.find("session ignored, opening with defaults"), std::string::npos) << note;
    EXPECT_NE(b.run.err.find(entry), std::string::npos) << b.run.err;
    if (bad.find("99") != std::string::npos) {
      EXPECT_NE(note.find("session version 99"), std::string::npos) << note;
    }
    EXPECT_NE(b.stats["camera"], a.stats["camera"]);
    EXPECT_NE(b.stats["playback"]["speed"], 3.5);
  }
  // Quitting saved that window's session over it: the next one restores it.
  const Played c = play(tsp, cache, "", dir / "c.json");
  EXPECT_TRUE(c.stats["session"]["restored"].get<bool>()) << c.stats["session"];
}

// File > Open (the script's open) keeps the session of the input played so far and restores the
// opened input's own.
TEST(Player, OpenKeepsTheSessionAndRestoresTheOpenedInputs) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path a = make_tsp(), b = make_tsp(), dir = tsptest::temp_dir();
  const std::string cache = " --cache-dir " + q(dir / "cache");
  const Played one = play(a, cache, "view 75 -30\nopen " + b.string() + "\n", dir / "1.json");
  ASSERT_EQ(one.run.exit_code, 0) << one.run.err;
  EXPECT_FALSE(one.stats["session"]["restored"].get<bool>());  // b has none yet
  EXPECT_EQ(one.stats["camera"]["azimuth_deg"], 30.0);         // b's start view
  const Played two = play(b, cache, "view 10 10\nopen " + a.string() + "\n", dir / "2.json");
  ASSERT_EQ(two.run.exit_code, 0) << two.run.err;
  EXPECT_TRUE(two.stats["session"]["restored"].get<bool>()) << two.stats["session"];
  EXPECT_EQ(two.stats["camera"]["azimuth_deg"], 75.0);  // kept when the first window opened b
  EXPECT_EQ(two.stats["camera"]["elevation_deg"], -30.0);
  const Played three = play(b, cache, "", dir / "3.json");
  EXPECT_EQ(three.stats["camera"]["azimuth_deg"], 10.0);  // kept when the second opened a
}

TEST(Player, SharedSessionOpensWithDashDashSession) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), shared = dir / "shared.json";
  const Played a = play(tsp, " --no-session", std::string(kChanges) + "save-session " +
                                                  shared.string() + "\n",
                        dir / "a.json");
  ASSERT_EQ(a.run.exit_code, 0) << a.run.err;
  ASSERT_TRUE(fs::is_regular_file(shared));
  EXPECT_EQ(read_json(shared)["version"], 1);
  // Another user's cache folder (the test's own is fresh): the shared file's settings.
  const Played b = play(tsp, " --session " + q(shared), "", dir / "b.json");
  ASSERT_EQ(b.run.exit_code, 0) << b.run.err;
  EXPECT_TRUE(b.stats["session"]["restored"].get<bool>());
  EXPECT_EQ(b.stats["session"]["from"], shared.string());
  EXPECT_EQ(kept(b.stats), kept(a.stats));
  // A bad --session is play's error, naming the file; so is a missing one.
  std::ofstream(dir / "bad.json") << R"({"version": 1, "camera": {"zoom": -2}})";
  for (const fs::path& bad : {dir / "bad.json", dir / "missing.json"}) {
    auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --session " + q(bad) +
                         " --screenshot " + q(dir / "x.png"));
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "x.png"));
  }
}

// The panel layout: a section closed with a real click (xdotool) on the docked side panel's first
// header is closed again in the next window on the same input. The steps wait on the player's
// --trace lines, not on the clock.
TEST(Player, OpenSectionsAreRestored) {
  TSPTEST_REQUIRE_X_EVENTS();
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), out = dir / "click.out";
  const std::string size = "760x400";  // docked: the side panel at x 390..760
  const std::string cache = " --cache-dir " + q(dir / "cache");
  const fs::path backstop = write_script(until_ctrl_q(dir));
  const std::string cmd =
      log_waits(out) + "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) + " --size " + size +
      cache + " --trace --frame-delay-ms 200 --script " + q(backstop) + " > " + q(out) +
      " 2>&1 &\n" +
      "w=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n"
      "until_log 'trace: tf canvas'\n"  // the panels are drawn
      "xdotool mousemove --window \"$w\" 450 38 click 1\n"
      "until_log 'trace: open sections {\"##side/##sections'\n"
      "quit_player)\n";
  ASSERT_EQ(run_bash(dir / "click.sh", cmd), 0) << tsptest::read_file(out);
  const Played b = play(tsp, cache, "wait-frames 3\n", dir / "b.json", size);
  ASSERT_EQ(b.run.exit_code, 0) << b.run.err;
  const nlohmann::json a = read_json(b.stats["session"]["from"].get<std::string>())["panels"]["open"];
  // The side panel's sections scroll in its child window "##side/##sections_…".
  std::string sections;
  for (const auto& [name, ids] : a.items())
    if (name.rfind("##side/##sections", 0) == 0) sections = name;
  ASSERT_FALSE(sections.empty()) << a << tsptest::read_file(out);
  EXPECT_EQ(a[sections].size(), 1u) << a;
  EXPECT_EQ(a[sections][0][1], 0) << a;  // a section open by default, closed
  EXPECT_EQ(b.stats["session"]["open_sections"], a);
  // With --no-session every section is as it starts.
  const Played c = play(tsp, cache + " --no-session", "wait-frames 3\n", dir / "c.json", size);
  ASSERT_EQ(c.run.exit_code, 0) << c.run.err;
  EXPECT_EQ(c.stats["session"]["open_sections"], nlohmann::json::object());
}

// Real X key events (xdotool) at about three frames a second: Ctrl+O opens File > Open with its
// path field taking the keys, and a Ctrl+A tapped between two frames selects the whole path, so
// the next key replaces it (Dear ImGui 1.86 alone misses a press shorter than a frame). Each step
// waits on the player's --trace lines; Ctrl+Q ends it.
TEST(Player, CtrlASelectsTheOpenDialogsPath) {
  TSPTEST_REQUIRE_X_EVENTS();
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), out = dir / "keys.out";
  const fs::path backstop = write_script(until_ctrl_q(dir));
  const std::string cmd =
      log_waits(out) + "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) +
      " --size 480x360 --trace --frame-delay-ms 300 --script " + q(backstop) + " > " + q(out) +
      " 2>&1 &\n" +
      "w=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n"
      "until_log 'trace: tf canvas'\n"
      + select_all_in_open_dialog() + "quit_player)\n";
  ASSERT_EQ(run_bash(dir / "keys.sh", cmd), 0) << tsptest::read_file(out);
  const std::string log = tsptest::read_file(out);
  EXPECT_NE(log.find("trace: open dialog"), std::string::npos) << log;
  // Typed into the field, then replaced whole: without the Ctrl+A the x went after "abc".
  expect_select_all_replaced(log);
}

}  // namespace

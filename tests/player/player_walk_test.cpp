// Issue 47's fifth fresh-eye walk: each finding reproduced by a small window (128x96, scripted)
// that failed before its fix. (Helpers: support/player_run.h.)
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/paths.h"
#include "support/player_run.h"
#include "tsp/report/image.h"

namespace {

namespace fs = std::filesystem;
using tsptest::q;
using tsptest::run_tspplay;
using namespace tsptest::player;

// Pixels drawn in the cut's level-0 green (80, 220, 80 at alpha 200): green well above red and
// blue, as the volume's auto map and the grey outline never are (the y axis is).
int green_pixels(const tsp::Image& im) {
  int n = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const std::uint8_t* p = im.at(x, y);
      n += p[1] > p[0] + 60 && p[1] > p[2] + 60;
    }
  return n;
}

// L (show cut) paused at full quality outlines the cut the picture was drawn with: every leaf
// brick in level 0's green. It drew only the adaptive cut of interaction, so paused (the
// picture refined in bands at full resolution) or playing at a rung it showed nothing.
TEST(PlayerWalk, ShowCutPausedOutlinesTheFullResolutionLeaves) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string on = (dir / "on.png").string(), off = (dir / "off.png").string();
  const auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --no-session --trace" +
                             " --script " +
                             q(write_script("panels off\nshow-cut on\nwait-frames 2\n"
                                            "screenshot-ui " + on + "\nshow-cut off\n"
                                            "wait-frames 1\nscreenshot-ui " + off + "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("trace: LOD cut: 8 nodes, full resolution (level 0)"), std::string::npos)
      << r.out;
  // (The axes triad's y axis is green too: in both.)
  EXPECT_GT(green_pixels(tsp::read_png(on)), green_pixels(tsp::read_png(off)) + 100);
}

// File > Open's message is an event, named as the user named the input: "playing PATH" (the
// cache's build) stayed in the status area while paused.
TEST(PlayerWalk, OpenSaysOpenedNotPlayingAndPausingLeavesNoPlayingMessage) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string a = (dir / "a.json").string(), b = (dir / "b.json").string();
  const auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --no-session --quality 0" +
                             " --script " +
                             q(write_script("open " + tsp.string() + "\nwait-frames 1\nstats " +
                                            a + "\nplay\nwait-frames 2\npause\nwait-frames 1\n"
                                            "stats " + b + "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_json(a)["status"], "opened " + tsp.string() + " (4 steps)");
  EXPECT_EQ(read_json(b)["status"].get<std::string>().find("playing"), std::string::npos)
      << read_json(b)["status"];
}

// As playback starts the timeline shows no rate until one was measured (a second step shown
// since it started): it read "playing at 0.0 steps/s of 24" (counted over the window's last
// 2 s, paused frames included). At 2 steps/s and 100 ms frames the second step comes after
// about five frames.
TEST(PlayerWalk, TheSpeedShowsNoRateUntilOneWasMeasured) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string a = (dir / "a.json").string(), b = (dir / "b.json").string();
  const auto r = run_tspplay(
      "play " + q(tsp) + " --size 740x344 --no-session --quality 0 --speed 2 --frame-delay-ms 100" +
      " --script " +
      q(write_script("wait-frames 3\nplay\nwait-frames 1\nstats " + a +
                     "\nwait-frames 12\nstats " + b + "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json ja = read_json(a), jb = read_json(b);
  EXPECT_TRUE(labels_with(ja, "steps/s of").empty()) << labels_with(ja, "steps/s of")[0];
  EXPECT_TRUE(labels_with(ja, "shown/s").empty());
  EXPECT_EQ(ja["playback"]["steps_shown_per_s"], 0);
  // Twelve frames (over 1.2 s) on, a second step was shown: a rate, and it is not zero.
  std::vector<std::string> rate = labels_with(jb, "steps/s of"), shown = labels_with(jb, "shown/s");
  rate.insert(rate.end(), shown.begin(), shown.end());
  ASSERT_EQ(rate.size(), 1u) << jb["ui_items"];
  EXPECT_EQ(rate[0].find(" 0.0 "), std::string::npos) << rate[0];
  EXPECT_GT(jb["playback"]["steps_shown_per_s"].get<double>(), 0);
}

// Every fit of the colour range is an edit the player sees (--trace "transfer function
// edited", the LOD loop, the tuning and the metric key on the TF's version): a fit replaced the
// TF by a copy that took the fitted table's version, so after the first, fits to step, view or
// data went unseen (the walk: only "fit to bulk" was traced).
TEST(PlayerWalk, EveryFitIsTracedAsAnEdit) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp();
  std::string script = "wait-frames 1\n";
  for (const char* fit : {"histogram", "step", "visible", "data"})
    script += std::string("tf-range 0.1:0.2\nwait-frames 1\ntf-range ") + fit + "\nwait-frames 1\n";
  const auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --no-session --trace" +
                             " --script " + q(write_script(script + "quit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int edits = 0;
  for (std::size_t at = r.out.find("trace: transfer function edited"); at != std::string::npos;
       at = r.out.find("trace: transfer function edited", at + 1))
    ++edits;
  EXPECT_EQ(edits, 8) << r.out;
}

// Issue 47's sixth walk: the cursor resting on the timeline, then one motion to the view with the
// button pressed there, and a drag 80 px to the right. The frame of the press carried the motion
// from the timeline as a drag, and the view flipped to nearly top-down. Now the view turns by
// the drag alone: the azimuth by at most 80 px × 0.4°, the elevation not at all.
TEST(PlayerWalk, AnOrbitStartsAtThePressNotWhereTheCursorCameFrom) {
  TSPTEST_REQUIRE_X_EVENTS();
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const fs::path out = dir / "orbit.out", stats = dir / "orbit.json";
  // (Each stage a handshake: the window has taken it before the next.)
  const fs::path script =
      write_script("panels off\nwait-frames 2\n" + taken(dir, "rest") + taken(dir, "press") +
                   taken(dir, "drag") + taken(dir, "release") + "stats " + stats.string() +
                   "\nquit\n");
  const std::string cmd =
      log_waits(out) + handshakes(dir) + "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) +
      " --size 400x400 --no-session --script " + q(script) + " > " + q(out) + " 2>&1 &\n" +
      "win=$(timeout 20 xdotool search --sync --name " + q("tspplay - " + tsp.string()) +
      " | head -1)\n"
      "xdotool mousemove --window \"$win\" 20 20; handshake rest\n"
      "xdotool mousemove --window \"$win\" 200 300 mousedown 1 mousemove --window \"$win\" 240 300\n"
      "handshake press; xdotool mousemove --window \"$win\" 280 300; handshake drag\n"
      "xdotool mouseup 1; handshake release\n"
      "wait)\n";
  ASSERT_EQ(run_bash(dir / "orbit.sh", cmd), 0);
  const nlohmann::json j = read_json(stats);
  const double azimuth = j["camera"]["azimuth_deg"], elevation = j["camera"]["elevation_deg"];
  EXPECT_NEAR(elevation, 20.0, 1.0) << read_text(out);  // the jump was 280 px up: +112°
  EXPECT_LE(azimuth, 30.0 - 40 * 0.4 + 1) << read_text(out);  // the drag's second half at least
  EXPECT_GE(azimuth, 30.0 - 80 * 0.4 - 1) << read_text(out);  // (the jump: 180 px more)
}

}  // namespace

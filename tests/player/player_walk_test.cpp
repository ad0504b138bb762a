// Issue 47's fifth fresh-eye walk: each finding reproduced by a small window (128x96, scripted)
// that failed before its fix. (Helpers: support/player_run.h.)
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

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

}  // namespace

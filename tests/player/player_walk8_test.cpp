// Issue 47's eighth fresh-eye walk: each finding reproduced by a small window (scripted, or
// driven by xdotool and waited on through --trace lines) that failed before its fix.
// (Helpers: support/player_run.h.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/paths.h"
#include "support/player_run.h"

namespace {

namespace fs = std::filesystem;
using tsptest::q;
using tsptest::run_tspplay;
using namespace tsptest::player;

// Occurrences of text in s.
int count(const std::string& s, const std::string& text) {
  int n = 0;
  for (std::size_t at = s.find(text); at != std::string::npos; at = s.find(text, at + 1)) ++n;
  return n;
}

// File > Open of a path that does not exist stays open with the error in it and the typed path
// kept: Enter again opens the same path (a second "opens" line, the same error), and Escape
// then closes the dialog (it was open). It used to close on Open, the error only in the status
// area, the path lost.
TEST(PlayerWalk8, AFailedOpenKeepsTheDialogOpenWithItsErrorAndPath) {
  TSPTEST_REQUIRE_X_EVENTS();
  const fs::path dir = tsptest::temp_dir(), out = dir / "open.out", tsp = dir / "s.tsp";
  fs::copy_file(make_tsp(), tsp);
  const fs::path missing = dir / "nope.h5";
  const fs::path backstop = write_script("wait-seconds 120\nquit\n");  // (if Ctrl+Q is lost)
  const std::string cmd =
      log_waits(out) + "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) +
      " --size 640x480 --cache-dir " + q(dir / "cache") + " --trace --script " + q(backstop) +
      " > " + q(out) + " 2>&1 &\n" + "w=$(xdotool search --sync --name " +
      q("tspplay - " + tsp.string()) + " | head -1)\n"
      "until_log 'trace: tf canvas'\n"
      "xdotool key --window \"$w\" ctrl+o\n"
      "until_log 'trace: open path field active'\n"
      "xdotool key --window \"$w\" End\n"
      "xdotool type --window \"$w\" nope.h5\n"
      "until_log " + q("trace: open path " + missing.string() + "$") + "\n"
      "xdotool key --window \"$w\" Return\n"
      "until_log " + q("trace: open dialog error: open " + missing.string()) + "\n"
      // The field has the keys again, the path in it: Enter opens the same path.
      "until_n 'trace: open path field active' 2\n"
      "xdotool key --window \"$w\" Return\n"
      "until_n " + q("trace: open dialog error: open " + missing.string()) + " 2\n"
      "xdotool key --window \"$w\" Escape\n"
      "until_log 'trace: open dialog closed'\n"
      "quit_player)\n";
  ASSERT_EQ(run_bash(dir / "open.sh", cmd), 0) << tsptest::read_file(out);
  const std::string log = tsptest::read_file(out);
  EXPECT_EQ(count(log, "trace: open dialog opens " + missing.string() + "\n"), 2) << log;
  EXPECT_EQ(count(log, "trace: open dialog closed"), 1) << log;
}

// A colour range typed, then a fit to the data, keep every point of the TF editor at its place
// relative to the range: six points (three added, one moved) stay six, where they were. A moved
// handle of the auto map stays moved. (Placed again from the stretched table, the points
// shifted and merged: a fit left 7 points of 9; the auto map's moved handle went back to 0.25.)
TEST(PlayerWalk8, ARangeChangeAndAFitKeepEveryPointInItsPlace) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string edits[] = {
      "tf preset:cool-to-warm\ntf-point add 0.3 0.5\ntf-point add 0.6 0.2\n"
      "tf-point add 0.8 0.9\ntf-point move 2 0.1 0.9\n",
      "tf preset:auto\ntf-point move 3 0.2 0.9\n"};
  int n = 0;
  for (const std::string& edit : edits) {
    const fs::path a = dir / (std::to_string(n) + "a.json"), b = dir / (std::to_string(n) + "b.json");
    const fs::path c = dir / (std::to_string(n) + "c.json");
    const fs::path script = dir / (std::to_string(n++) + ".txt");
    std::ofstream(script) << edit << "tf-range data\nwait-frames 1\nstats " << a.string()
                          << "\ntf-range 0.3:2.5\nwait-frames 1\nstats " << b.string()
                          << "\ntf-range data\nwait-frames 1\nstats " << c.string() << "\nquit\n";
    const auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --no-session --script " +
                               q(script));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json ja = read_json(a), jb = read_json(b), jc = read_json(c);
    // Each point's place in its range.
    auto places = [](const nlohmann::json& j) {
      std::vector<double> u;
      const double lo = j["tf_domain"][0], hi = j["tf_domain"][1];
      for (const auto& p : j["tf_points"]) u.push_back((p[0].get<double>() - lo) / (hi - lo));
      return u;
    };
    const std::vector<double> ua = places(ja), ub = places(jb), uc = places(jc);
    EXPECT_EQ(jb["tf_domain"][0].get<double>(), 0.3);
    ASSERT_EQ(ub.size(), ua.size()) << edit;
    ASSERT_EQ(uc.size(), ua.size()) << edit;
    for (std::size_t i = 0; i < ua.size(); ++i) {
      EXPECT_NEAR(ub[i], ua[i], 1e-9) << edit << i;
      EXPECT_NEAR(uc[i], ua[i], 1e-9) << edit << i;
    }
    // The moved handle (0.1 or 0.2 of the range) is still there.
    const double moved = n == 1 ? 0.1 : 0.2;
    bool found = false;
    for (double u : uc) found = found || std::fabs(u - moved / ja["tf_domain"][1].get<double>()) < 1e-6;
    EXPECT_TRUE(found) << edit << ja["tf_points"] << jc["tf_points"];
  }
}

// The point list's opacity values are readable: each point's opacity is printed as its own item
// beside its slider (ImGui centred it on the slider, where the grab covered it), inside the
// panel, in the format of the axis (log: 1.00e-04). Before, no such item existed.
TEST(PlayerWalk8, ThePointListPrintsEachOpacityBesideItsSlider) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const fs::path lin = dir / "lin.json", log = dir / "log.json";
  const fs::path script = dir / "points.txt";
  std::ofstream(script) << "tf preset:cool-to-warm\ntf-point add 0.3 0.25\nexpand on\n"
                           "wait-frames 3\nstats " << lin.string() << "\nlog-opacity on\n"
                           "wait-frames 3\nstats " << log.string() << "\nquit\n";
  const auto r = run_tspplay("play " + q(tsp) + " --size 1280x800 --no-session --script " +
                             q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const auto& [file, format] : {std::pair{lin, "%.3f"}, std::pair{log, "%.2e"}}) {
    const nlohmann::json j = read_json(file);
    ASSERT_EQ(j["tf_points"].size(), 4u);
    for (const auto& p : j["tf_points"]) {
      char value[32];
      std::snprintf(value, sizeof value, format, p[1].get<double>());
      const std::vector<std::string> found = labels_with(j, value);
      ASSERT_FALSE(found.empty()) << value << " " << j["ui_items"];
      bool inside = false;
      for (const auto& it : j["ui_items"])
        if (it["label"] == value)
          inside = inside || (it["text_w"].get<double>() <= it["w"].get<double>() + 0.5 &&
                              it["x"].get<double>() + it["w"].get<double>() <=
                                  it["clip_right"].get<double>() + 0.5);
      EXPECT_TRUE(inside) << value;
    }
  }
}

// S saves beside the data (not in the working directory), named by dataset, field and step,
// never over an existing file (-2, -3, …), and the status line names the full path; after a
// dialog saved a file elsewhere (save-session), S saves there.
TEST(PlayerWalk8, SSavesBesideTheDataNeverOverAnEarlierFile) {
  TSPTEST_REQUIRE_X_EVENTS();
  const fs::path dir = tsptest::temp_dir(), out = dir / "s.out";
  fs::create_directories(dir / "data");
  fs::create_directories(dir / "work");
  fs::create_directories(dir / "shared");
  const fs::path tsp = dir / "data" / "s.tsp";
  fs::copy_file(make_tsp(), tsp);
  const fs::path earlier = dir / "data" / "s_shock_step_0000.png";
  std::ofstream(earlier) << "an earlier picture";
  const fs::path script = write_script("wait-frames 2\nstats " + (dir / "a.json").string() +
                                       "\nwait-seconds 120\nquit\n");
  const fs::path shared_session = dir / "shared" / "mine.session.json";
  const fs::path script2 = write_script("save-session " + shared_session.string() +
                                        "\nwait-frames 2\nstats " + (dir / "b.json").string() +
                                        "\nwait-seconds 120\nquit\n");
  auto run = [&](const fs::path& sc, const fs::path& ready, int presses) {
    return "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) + " --size " + kSize +
           " --no-session --script " + q(sc) + " > " + q(out) + " 2>&1 &\n" +
           "w=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n" +
           "for i in $(seq 600); do [ -f " + q(ready) + " ] && break; sleep 0.1; done\n" +
           "for k in $(seq " + std::to_string(presses) + "); do xdotool key --window \"$w\" s\n"
           "  until_n '^saved ' $k; done\n"
           "quit_player)\n";
  };
  const std::string cmd = "cd " + q(dir / "work") + "\n" + log_waits(out) +
                          run(script, dir / "a.json", 2) + "cp " + q(out) + " " +
                          q(dir / "first.out") + "\n" + run(script2, dir / "b.json", 1);
  ASSERT_EQ(run_bash(dir / "s.sh", cmd), 0) << tsptest::read_file(out);
  const std::string first = tsptest::read_file(dir / "first.out");
  EXPECT_EQ(tsptest::read_file(earlier), "an earlier picture");
  const fs::path second = dir / "data" / "s_shock_step_0000-2.png", third = dir / "data" / "s_shock_step_0000-3.png";
  EXPECT_TRUE(fs::exists(second)) << first;
  EXPECT_TRUE(fs::exists(third)) << first;
  EXPECT_NE(first.find("saved " + second.string() + "\n"), std::string::npos) << first;
  EXPECT_NE(first.find("saved " + third.string() + "\n"), std::string::npos) << first;
  EXPECT_TRUE(fs::is_empty(dir / "work"));
  // After a session saved to shared/, S saves there too.
  const std::string log = tsptest::read_file(out);
  const fs::path there = dir / "shared" / "s_shock_step_0000.png";
  EXPECT_TRUE(fs::exists(there)) << log;
  EXPECT_NE(log.find("saved " + there.string() + "\n"), std::string::npos) << log;
}

}  // namespace

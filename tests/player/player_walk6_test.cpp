// Issue 47's sixth fresh-eye walk: each finding reproduced by a small window (128x96, scripted)
// that failed before its fix. (Helpers: support/player_run.h.)
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "player/command.h"
#include "player/script.h"
#include "support/paths.h"
#include "support/player_run.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"
#include "tsp/metric/tf_io.h"

namespace {

namespace fs = std::filesystem;
using tsptest::q;
using tsptest::run_tspplay;
using namespace tsptest::player;

// Each line of a capture folder's frames.jsonl.
std::vector<nlohmann::json> captured(const fs::path& dir) {
  std::vector<nlohmann::json> frames;
  std::ifstream in(dir / "frames.jsonl");
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) frames.push_back(nlohmann::json::parse(line));
  return frames;
}

// Space pauses on the step on screen when it went down, with its picture (a real X key,
// xdotool): pressed while a slow frame draws step 2 (step 1 on screen, "trace: step 2" printed
// as that frame began), the frame of step 2 is dropped and playback stops on step 1. Every frame
// drawn (script capture) shows steps in order, never step 2 and never a step back; after the
// pause each frame is at least as close to step 1's full-quality picture as the last playing
// frame (the bands refine it; a coarser cut is never drawn). It paused on step 2, a step late;
// the reverted fix (7d17e86) went back to step 1 from step 2's picture through a coarse cut.
TEST(PlayerWalk6, SpacePausesOnTheStepOnScreenWithItsPicture) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  ASSERT_EQ(std::system("command -v xdotool > /dev/null"), 0)
      << "xdotool missing (scripts/install-deps.sh installs it)";
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), out = dir / "space.out";
  const fs::path cap = dir / "cap";
  const fs::path script =
      write_script("capture " + cap.string() + "\nplay\n" + until_ctrl_q(dir));
  const std::string jsonl = q(cap / "frames.jsonl");
  const std::string cmd =
      log_waits(out) + "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) + " --size " + kSize +
      " --no-session --quality 0 --speed 24 --trace --frame-delay-ms 800 --script " + q(script) +
      " > " + q(out) + " 2>&1 &\n" + "w=$(xdotool search --sync --name " +
      q("tspplay - " + tsp.string()) + " | head -1)\n"
      "until_log 'trace: step 2'\n"
      "xdotool key --window \"$w\" space\n"
      "until_log 'trace: paused'\n"
      // (the refinement done: the last frame captured is at full quality)
      "for i in $(seq 600); do tail -1 " + jsonl + " | grep -q '\"stage\":\"full\"' && break; "
      "sleep 0.1; done\n"
      "quit_player)\n";
  ASSERT_EQ(run_bash(dir / "space.sh", cmd), 0) << tsptest::read_file(out);
  const std::string log = tsptest::read_file(out);
  EXPECT_NE(log.find("trace: frame of step 2 dropped: Space went down while it was drawn; step 1 "
                     "stays"),
            std::string::npos)
      << log;
  const std::size_t last = log.rfind("trace: step ");
  EXPECT_EQ(log.substr(last, log.find('\n', last) - last), "trace: step 1") << log;

  const std::vector<nlohmann::json> frames = captured(cap);
  ASSERT_FALSE(frames.empty());
  std::size_t paused = 0;  // the first paused frame
  for (std::size_t k = 0; k < frames.size(); ++k) {
    EXPECT_LE(frames[k]["step"].get<int>(), 1) << frames[k].dump();
    if (k > 0) {
      EXPECT_GE(frames[k]["step"].get<int>(), frames[k - 1]["step"].get<int>());
    }
    if (!paused && k > 0 && !frames[k]["playing"].get<bool>()) paused = k;
  }
  ASSERT_GT(paused, 0u);
  EXPECT_EQ(frames.back()["stage"], "full") << frames.back().dump();
  // Against step 1 at full quality: the last playing frame, then never further.
  const tsp::Image full = render_step(tsp, 1);
  auto de = [&](std::size_t k) {
    return tsp::diff_images(tsp::read_png((cap / frames[k]["file"].get<std::string>()).string()),
                            full).mean;
  };
  // The frame that dropped step 2 showed step 1's picture as it was on screen.
  ASSERT_GE(paused, 2u);
  EXPECT_EQ(frames[paused - 2]["step"], 1);
  const auto png = [&](std::size_t k) {
    return tsp::read_png((cap / frames[k]["file"].get<std::string>()).string());
  };
  EXPECT_EQ(tsp::diff_images(png(paused - 2), png(paused - 1)).mean, 0.0);
  double before = de(paused - 1);
  for (std::size_t k = paused; k < frames.size(); ++k) {
    const double now = de(k);
    EXPECT_LE(now, before + 0.05) << "frame " << k << ": " << frames[k].dump();
    before = std::min(before, now);
  }
  EXPECT_LT(de(frames.size() - 1), kSameFrameDeltaE);
}

// The F1 help overlay is opaque: shown (a real F1, xdotool) over two different pictures (the
// view turned between two screenshots with the UI), the overlay's body, which covers the middle
// of the 128x96 window, reads the same in both. On Dear ImGui's 94 % window background the picture showed through.
TEST(PlayerWalk6, TheHelpOverlayHidesThePictureBehindIt) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  ASSERT_EQ(std::system("command -v xdotool > /dev/null"), 0)
      << "xdotool missing (scripts/install-deps.sh installs it)";
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), out = dir / "help.out";
  const fs::path a = dir / "a.png", b = dir / "b.png";
  const fs::path script = write_script("panels off\ntf preset:filled\n" + taken(dir, "f1") +
                                       "screenshot-ui " + a.string() + "\nview 120 70\nzoom 1.5\nwait-frames 2\n"
                                       "screenshot-ui " + b.string() + "\nquit\n");
  const std::string cmd =
      log_waits(out) + handshakes(dir) + "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) +
      " --size " + kSize + " --no-session --trace --script " + q(script) + " > " + q(out) +
      " 2>&1 &\n" + "w=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) +
      " | head -1)\n"
      "until_log 'trace: step 0'\n"
      "xdotool key --window \"$w\" F1\n"
      "handshake f1\n"
      "wait)\n";
  ASSERT_EQ(run_bash(dir / "help.sh", cmd), 0) << tsptest::read_file(out);
  const tsp::Image ia = tsp::read_png(a.string()), ib = tsp::read_png(b.string());
  // The overlay's body (under its title bar, inside its edges): the same pixels in both.
  int differ = 0;
  for (int y = 30; y < 80; ++y)
    for (int x = 8; x < 100; ++x)
      for (int c = 0; c < 3; ++c) differ += ia.at(x, y)[c] != ib.at(x, y)[c];
  EXPECT_EQ(differ, 0) << tsptest::read_file(out);
  // (Outside it, where the volume shows, the pictures differ: the view turned.)
  EXPECT_GT(tsp::diff_images(ia, ib).mean, 0.0);
}

// Occurrences of text in s.
int count(const std::string& s, const std::string& text) {
  int n = 0;
  for (std::size_t at = s.find(text); at != std::string::npos; at = s.find(text, at + 1)) ++n;
  return n;
}

// One change of the axis scale, one trace line: the walk saw "trace: axis scale 1,1,10" twice
// for one typed value (the field sent it twice); a scale set again to what it is changes nothing
// and prints nothing.
TEST(PlayerWalk6, OneAxisScaleChangeIsTracedOnce) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp();
  const auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --no-session --trace" +
                             " --script " +
                             q(write_script("scale 1,1,7\nwait-frames 1\nscale 1,1,7\n"
                                            "wait-frames 1\nscale 1,1,1\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(count(r.out, "trace: axis scale 1,1,7\n"), 1) << r.out;
  EXPECT_EQ(count(r.out, "trace: axis scale 1,1,1\n"), 1) << r.out;
}

// A fit of the colour range that moves nothing says so: the second "fit to bulk" in a row left
// the map as it was and said nothing (no trace, no status), as if the button did not work.
TEST(PlayerWalk6, AFitThatChangesNothingSaysSo) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string a = (dir / "a.json").string();
  const auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --no-session --trace" +
                             " --script " +
                             q(write_script("wait-frames 1\ntf-range 0.1:0.2\nwait-frames 1\n"
                                            "tf-range bulk\nwait-frames 1\ntf-range bulk\n"
                                            "wait-frames 1\nstats " + a + "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(count(r.out, "trace: transfer function edited"), 2) << r.out;
  EXPECT_EQ(count(r.out, "trace: colour range already fits the bulk ["), 1) << r.out;
  const std::string status = read_json(a)["status"];
  EXPECT_EQ(status.rfind("colour range already fits the bulk [", 0), 0u) << status;
  EXPECT_NE(status.find("]: nothing changed"), std::string::npos) << status;
  EXPECT_FALSE(read_json(a)["status_error"]);  // a message, not an error: amber
  EXPECT_EQ(status.find("000000"), std::string::npos) << status;  // 6 digits, not "-0.000000"
}

// The colour range's words are the fit buttons' names: each "fit to WORD" in the panel is a
// word the script's tf-range (and --tf-range) takes, and the old words stay as aliases. The
// buttons read "fit to bulk" and "fit to view" while the script took "histogram" and "visible".
TEST(PlayerWalk6, TheColourRangeWordsAreTheFitButtonsNames) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string a = (dir / "a.json").string();
  const auto r = run_tspplay("play " + q(tsp) + " --size 740x600 --no-session --script " +
                             q(write_script("wait-frames 2\nstats " + a + "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> fits = labels_with(read_json(a), "fit to ");
  ASSERT_EQ(fits.size(), 4u) << read_json(a)["ui_items"];
  for (const std::string& label : fits) {
    const std::string word = label.substr(std::string("fit to ").size());
    EXPECT_NO_THROW(tspplayer::validate(tspplayer::cmd::StretchTf{word})) << word;
    EXPECT_EQ(tspplayer::parse_script("tf-range " + word + "\n", "s.txt").size(), 1u) << word;
    EXPECT_NO_THROW(tsp::parse_tf_range(word)) << word;
  }
  for (const char* old : {"histogram", "visible"})
    EXPECT_NO_THROW(tspplayer::validate(tspplayer::cmd::StretchTf{old})) << old;
}

// An error leaves the status area when the next action succeeds: File > Open of a missing input
// said so, and the message stayed there for the rest of the session, through steps, fits and
// views. Waits and stats are no actions: it stays through them.
TEST(PlayerWalk6, AnErrorClearsWhenTheNextActionSucceeds) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string a = (dir / "a.json").string(), b = (dir / "b.json").string();
  const std::string missing = (dir / "missing.h5").string();
  const auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --no-session --trace" +
                             " --script " +
                             q(write_script("open " + missing + "\nwait-frames 2\nstats " + a +
                                            "\nstep 1\nwait-frames 1\nstats " + b +
                                            "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string before = read_json(a)["status"];
  EXPECT_EQ(before.rfind("open " + missing, 0), 0u) << before;
  EXPECT_TRUE(read_json(a)["status_error"]) << before;  // drawn in red (the seventh walk)
  EXPECT_EQ(read_json(b)["status"], "") << r.out;
  EXPECT_FALSE(read_json(b)["status_error"]);
  EXPECT_EQ(count(r.out, "trace: error cleared: the next action succeeded"), 1) << r.out;
}

// File > Save session offers a file named after the dataset beside the data (it offered
// tspplay_session.json in the working directory for every input), then in the folder a session
// was last saved to.
TEST(PlayerWalk6, SaveSessionOffersTheDatasetsNameBesideIt) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), other = dir / "other";
  fs::create_directories(other);
  const std::string name = tsp.stem().string() + ".session.json";
  const auto r = run_tspplay(
      "play " + q(tsp) + " --size 740x600 --no-session --trace --script " +
      q(write_script("dialog save-session\nwait-frames 2\ndialog close\nwait-frames 2\n"
                     "save-session " + (other / "mine.json").string() + "\n"
                     "dialog save-session\nwait-frames 2\ndialog close\nwait-frames 2\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("trace: save session dialog offers " + (tsp.parent_path() / name).string() +
                       "\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("trace: save session dialog offers " + (other / name).string() + "\n"),
            std::string::npos)
      << r.out;
}

// A speed set in the window belongs to its series: File > Open of another input starts at that
// input's default (the seventh walk: the plume's 6 steps/s went on to the 2-step dam break and
// into its session); --speed is kept.
TEST(PlayerWalk7, ASpeedSetInTheWindowStaysWithItsSeries) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string a = (dir / "a.json").string(), b = (dir / "b.json").string();
  const std::string script = "speed 6\nstats " + a + "\nopen " + tsp.string() +
                             "\nwait-frames 2\nstats " + b + "\nquit\n";
  auto played = [&](const std::string& extra) {
    const auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --no-session" + extra +
                               " --script " + q(write_script(script)));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return std::pair{read_json(a)["playback"]["speed"].get<double>(),
                     read_json(b)["playback"]["speed"].get<double>()};
  };
  const auto window = played("");
  EXPECT_EQ(window.first, 6.0);
  EXPECT_EQ(window.second, 1.0);  // make_tsp's 4 steps over the default loop's 4 s (docs/player.md)
  const auto given = played(" --speed 2");
  EXPECT_EQ(given.second, 2.0);  // the command line's speed is kept
}

// Playing shows a frame before the tuning's first probe picture: Space showed nothing for
// 2.7 s on the demo while the first full-quality probe was drawn in the frame the key arrived
// (the seventh walk). A fresh cache: the tuning runs.
TEST(PlayerWalk7, PlayingDrawsAFrameBeforeTheTuningsFirstPicture) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string a = (dir / "a.json").string();
  const auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --no-session --cache-dir " +
                             q(dir / "cache") + " --script " +
                             q(write_script("play\nstats " + a + "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = read_json(a);
  EXPECT_TRUE(j["playback"]["tuned"].get<bool>()) << j["tuning"];
  EXPECT_FALSE(j["tuning"]["from_cache"].get<bool>()) << j["tuning"];
  EXPECT_GE(j["tuning"]["frames_before_first_picture"].get<int>(), 1) << j["tuning"];
}

}  // namespace

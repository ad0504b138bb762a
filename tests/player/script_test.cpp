// The player's action script parser: every action with its arguments, comments and blank
// lines, and errors naming the origin, the line and what was expected.
#include "player/script.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"

namespace {

using tspplayer::parse_script;
using Kind = tspplayer::ScriptAction::Kind;

std::string error_of(const std::string& text) {
  return tsptest::error_of<tsp::FormatError>([&] { parse_script(text, "s.txt"); });
}

TEST(PlayerScript, ParsesEveryAction) {
  const auto a = parse_script(
      "# a comment\n"
      "\n"
      "step 3\nplay\npause\nspeed 2.5\nloop off\ntf preset:filled\ntolerance 0.1 0.02\n"
      "metric perceptual\ncache on\nprefetch off\nupload-budget 16\nview 30 -20\nzoom 1.5\n"
      "projection persp\nscreenshot a.png\nscreenshot-ui b.png\nwait-frames 4\n   quit   \n",
      "s.txt");
  ASSERT_EQ(a.size(), 18u);
  EXPECT_EQ(a[0].kind, Kind::step);
  EXPECT_EQ(a[0].number, 3);
  EXPECT_EQ(a[0].line, 3);
  EXPECT_EQ(a[1].kind, Kind::play);
  EXPECT_EQ(a[2].kind, Kind::pause);
  EXPECT_EQ(a[3].kind, Kind::speed);
  EXPECT_DOUBLE_EQ(a[3].value, 2.5);
  EXPECT_EQ(a[4].kind, Kind::loop);
  EXPECT_FALSE(a[4].flag);
  EXPECT_EQ(a[5].kind, Kind::tf);
  EXPECT_EQ(a[5].text, "preset:filled");
  EXPECT_EQ(a[6].kind, Kind::tolerance);
  EXPECT_DOUBLE_EQ(a[6].value, 0.1);
  EXPECT_DOUBLE_EQ(a[6].value2, 0.02);
  EXPECT_EQ(a[7].text, "perceptual");
  EXPECT_TRUE(a[8].flag);
  EXPECT_EQ(a[9].kind, Kind::prefetch);
  EXPECT_FALSE(a[9].flag);
  EXPECT_EQ(a[10].kind, Kind::setting);
  EXPECT_EQ(a[10].text, "upload-budget");
  EXPECT_EQ(a[10].text2, "16");
  EXPECT_EQ(a[11].kind, Kind::view);
  EXPECT_DOUBLE_EQ(a[11].value2, -20);
  EXPECT_DOUBLE_EQ(a[12].value, 1.5);
  EXPECT_TRUE(a[13].flag);
  EXPECT_EQ(a[14].kind, Kind::screenshot);
  EXPECT_EQ(a[15].kind, Kind::screenshot_ui);
  EXPECT_EQ(a[15].text, "b.png");
  EXPECT_EQ(a[16].number, 4);
  EXPECT_EQ(a[17].kind, Kind::quit);
  EXPECT_EQ(a[17].line, 20);
  EXPECT_TRUE(parse_script("", "empty").empty());
  const auto k = parse_script(
      "compositing boxes\nspacing 2.5\npreintegrated on\nquality 1.5\nstats s.json\n", "k.txt");
  ASSERT_EQ(k.size(), 5u);
  EXPECT_EQ(k[0].kind, Kind::setting);
  EXPECT_EQ(k[0].text, "compositing");
  EXPECT_EQ(k[0].text2, "boxes");
  EXPECT_EQ(k[1].kind, Kind::setting);
  EXPECT_EQ(k[1].text, "spacing");
  EXPECT_EQ(k[1].text2, "2.5");
  EXPECT_EQ(k[2].kind, Kind::setting);
  EXPECT_EQ(k[2].text, "preintegrated");
  EXPECT_EQ(k[2].text2, "on");
  EXPECT_EQ(k[3].kind, Kind::quality);
  EXPECT_DOUBLE_EQ(k[3].value, 1.5);
  EXPECT_EQ(k[4].kind, Kind::stats);
  EXPECT_EQ(k[4].text, "s.json");
  const auto st = parse_script("sampling-tol 0.05\n", "st.txt");
  ASSERT_EQ(st.size(), 1u);
  EXPECT_EQ(st[0].kind, Kind::setting);
  EXPECT_EQ(st[0].text, "sampling-tol");
  EXPECT_EQ(st[0].text2, "0.05");
  // Every row of the settings table is an action, validated by the table when parsed.
  const auto d = parse_script("span-step mean\nflat slices\nreuse off\ndense off\n"
                              "skip-transparent off\n", "d.txt");
  ASSERT_EQ(d.size(), 5u);
  for (const tspplayer::ScriptAction& x : d) EXPECT_EQ(x.kind, Kind::setting);
  EXPECT_EQ(d[4].text, "skip-transparent");
  const auto l = parse_script("lod off\ntarget-fps 25\nshow-cut on\nwait-seconds 0.5\n", "l.txt");
  ASSERT_EQ(l.size(), 4u);
  EXPECT_EQ(l[0].kind, Kind::lod);
  EXPECT_FALSE(l[0].flag);
  EXPECT_EQ(l[1].kind, Kind::target_fps);
  EXPECT_DOUBLE_EQ(l[1].value, 25);
  EXPECT_EQ(l[2].kind, Kind::show_cut);
  EXPECT_TRUE(l[2].flag);
  EXPECT_EQ(l[3].kind, Kind::wait_seconds);
  EXPECT_DOUBLE_EQ(l[3].value, 0.5);
  const auto f = parse_script("panels off\nevery-step on\nlog-opacity on\nopen a.tsp\n"
                              "open raw.h5 U:mag\nrecord m.mp4\nrecord stop\n"
                              "open u_%04d.raw --raw-dims 8,6,4 --raw-type u8\n"
                              "open m.q Pressure --xyz g.xyz\n",
                              "f.txt");
  ASSERT_EQ(f.size(), 9u);
  EXPECT_EQ(f[0].kind, Kind::panels);
  EXPECT_FALSE(f[0].flag);
  EXPECT_EQ(f[1].kind, Kind::every_step);
  EXPECT_TRUE(f[1].flag);
  EXPECT_EQ(f[2].kind, Kind::log_opacity);
  EXPECT_EQ(f[3].kind, Kind::open);
  EXPECT_EQ(f[3].text, "a.tsp");
  EXPECT_EQ(f[3].text2, "");
  EXPECT_EQ(f[4].text2, "U:mag");
  EXPECT_EQ(f[5].kind, Kind::record);
  EXPECT_EQ(f[5].text, "m.mp4");
  EXPECT_EQ(f[6].kind, Kind::record_stop);
  EXPECT_EQ(f[7].text, "u_%04d.raw");
  EXPECT_EQ(f[7].text2, "");
  EXPECT_EQ(f[7].text3, "--raw-dims 8,6,4 --raw-type u8");
  EXPECT_EQ(f[8].text2, "Pressure");
  EXPECT_EQ(f[8].text3, "--xyz g.xyz");
  const auto g = parse_script("probe sphere:1,2,3,4\nprobe-op union\nprobe-surface off\n"
                              "probe-move 1 0.5 0 -2\nprobe-clear\nfield p\n",
                              "g.txt");
  ASSERT_EQ(g.size(), 6u);
  EXPECT_EQ(g[0].kind, Kind::probe);
  EXPECT_EQ(g[0].text, "sphere:1,2,3,4");
  EXPECT_EQ(g[1].kind, Kind::probe_op);
  EXPECT_EQ(g[2].kind, Kind::probe_surface);
  EXPECT_FALSE(g[2].flag);
  EXPECT_EQ(g[3].kind, Kind::probe_move);
  EXPECT_EQ(g[3].number, 1);
  EXPECT_DOUBLE_EQ(g[3].value3, -2);
  EXPECT_EQ(g[4].kind, Kind::probe_clear);
  EXPECT_EQ(g[5].kind, Kind::field);
  EXPECT_EQ(g[5].text, "p");
}

TEST(PlayerScript, ErrorsNameTheLineAndWhatWasExpected) {
  EXPECT_NE(error_of("play\nstep x\n").find("s.txt:2: 'x' is not an integer >= 0"),
            std::string::npos);
  EXPECT_NE(error_of("step 1 2").find("'step' takes 1 argument(s)"), std::string::npos);
  EXPECT_NE(error_of("jump 3").find("unknown action 'jump'"), std::string::npos);
  EXPECT_NE(error_of("loop maybe").find("expected on or off"), std::string::npos);
  EXPECT_NE(error_of("metric fancy").find("unknown metric 'fancy'"), std::string::npos);
  EXPECT_NE(error_of("speed 0").find("speed must be positive"), std::string::npos);
  EXPECT_NE(error_of("speed nan").find("speed must be positive"), std::string::npos);
  EXPECT_NE(error_of("tolerance -1 0").find("finite and not negative"), std::string::npos);
  EXPECT_NE(error_of("view 0 90").find("elevation must be in (-90, 90)"), std::string::npos);
  EXPECT_NE(error_of("zoom -2").find("zoom must be positive"), std::string::npos);
  EXPECT_NE(error_of("upload-budget -1").find("expected a number in [0, 1.04858e+06] (MiB)"),
            std::string::npos);
  EXPECT_NE(error_of("wait-frames -1").find("not an integer >= 0"), std::string::npos);
  EXPECT_NE(error_of("projection iso").find("expected persp or ortho"), std::string::npos);
  EXPECT_NE(error_of("speed 1e999").find("s.txt:1"), std::string::npos);
  EXPECT_NE(error_of("compositing voxels").find("expected slices, boxes or rays"),
            std::string::npos);
  EXPECT_NE(error_of("spacing 0").find("spacing '0': expected a number in [0.015625, 64] (voxels)"),
            std::string::npos);
  EXPECT_NE(error_of("sampling-tol -1").find("sampling-tol '-1': expected a finite number >= 0"),
            std::string::npos);
  EXPECT_NE(error_of("span-step last").find("expected first, middle or mean"), std::string::npos);
  EXPECT_NE(error_of("spacing").find("'spacing' takes 1 argument(s)"), std::string::npos);
  EXPECT_NE(error_of("quality -1").find("quality must be a mean dE in [0, 50]"), std::string::npos);
  EXPECT_NE(error_of("target-fps 0").find("target-fps must be 1 to"), std::string::npos);
  EXPECT_NE(error_of("lod maybe").find("expected on or off"), std::string::npos);
  EXPECT_NE(error_of("wait-seconds -1").find("wait-seconds must be"), std::string::npos);
  EXPECT_NE(error_of("record m.avi").find("expected a .mp4 or .gif file name, or stop"),
            std::string::npos);
  EXPECT_NE(error_of("open").find("'open' takes a path"), std::string::npos);
  EXPECT_NE(error_of("tf-range file").find("data, histogram, step, visible or LO:HI"), std::string::npos);
  EXPECT_NE(error_of("tf-range 3:1").find("expected auto, data, file, histogram, step, visible or"),
            std::string::npos) << error_of("tf-range 3:1");
  EXPECT_EQ(parse_script("tf-range histogram\ntf-range -1:2\n", "r.txt")[1].text, "-1:2");
  EXPECT_EQ(parse_script("tf-range step\n", "r.txt")[0].text, "step");
  EXPECT_EQ(parse_script("tf-range visible\n", "r.txt")[0].text, "visible");
  EXPECT_NE(error_of("open a.raw U V").find("expected 'open PATH [FIELD] [--OPTION"),
            std::string::npos);
  EXPECT_NE(error_of("panels maybe").find("expected on or off"), std::string::npos);
  EXPECT_NE(error_of("probe cone:1").find("expected plane"), std::string::npos);
  EXPECT_NE(error_of("probe-op xor").find("expected intersect, union or subtract"),
            std::string::npos);
  EXPECT_NE(error_of("probe-move 0 1 2 3").find("not an integer >= 1"), std::string::npos);
}

TEST(PlayerScript, LoadsAFileAndNamesAMissingOne) {
  const auto dir = tsptest::temp_dir();
  std::ofstream(dir / "s.txt") << "step 2\nquit\n";
  const auto a = tspplayer::load_script((dir / "s.txt").string());
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0].number, 2);
  try {
    tspplayer::load_script((dir / "none.txt").string());
    FAIL() << "no error";
  } catch (const tsp::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("none.txt"), std::string::npos);
  }
}

}  // namespace

namespace {

// Keys and panels make commands too; one validate() checks them, with the script's messages.
TEST(PlayerScript, CommandsFromKeysAndPanelsAreValidatedByTheSameRules) {
  using tspplayer::command_of;
  using tspplayer::ScriptAction;
  using tspplayer::validate;
  ScriptAction speed = command_of(ScriptAction::Kind::speed);
  speed.value = 100;
  EXPECT_THROW(validate(speed), tsp::UsageError);
  speed.value = 5;
  EXPECT_NO_THROW(validate(speed));
  ScriptAction spacing = command_of(ScriptAction::Kind::setting);
  spacing.text = "spacing";
  spacing.text2 = "0";
  const std::string from_panel =
      tsptest::error_of<tsp::UsageError>([&] { validate(spacing); });
  const std::string from_script = tsptest::error_of<tsp::FormatError>(
      [] { tspplayer::parse_script("spacing 0\n", "s.txt"); });
  EXPECT_NE(from_panel, "");
  EXPECT_EQ(from_script, "s.txt:1: " + from_panel);
  EXPECT_EQ(tspplayer::step_command(7).number, 7);
  EXPECT_TRUE(command_of(ScriptAction::Kind::loop, true).flag);
  EXPECT_EQ(tspplayer::parse_script("reset-camera\n", "r.txt")[0].kind,
            ScriptAction::Kind::reset_camera);
}

// Issue 48: a wait of 0 frames or seconds lets the script go on in the same frame (a million
// `wait-frames 0` lines cost a frame each, 45 minutes); screenshots and real waits stop it.
TEST(PlayerScript, WaitsOfZeroCostNoFrame) {
  using tspplayer::waits_for_frames;
  const auto a = parse_script(
      "wait-frames 0\nwait-seconds 0\nwait-frames 1\nwait-seconds 0.5\nscreenshot a.png\n"
      "screenshot-ui b.png\nstep 2\nquit\n",
      "w.txt");
  ASSERT_EQ(a.size(), 8u);
  const bool expected[8] = {false, false, true, true, true, true, false, false};
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(waits_for_frames(a[i]), expected[i]) << i;
}

}  // namespace

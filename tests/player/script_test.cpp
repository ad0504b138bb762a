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

using tspplayer::Command;
using tspplayer::parse_script;
namespace cmd = tspplayer::cmd;

std::string error_of(const std::string& text) {
  return tsptest::error_of<tsp::FormatError>([&] { parse_script(text, "s.txt"); });
}

// The commands of a script, in order.
std::vector<Command> commands_of(const std::string& text) {
  std::vector<Command> out;
  for (const tspplayer::ScriptLine& l : parse_script(text, "s.txt")) out.push_back(l.command);
  return out;
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
  const std::vector<Command> expected = {
      cmd::GoToStep{3}, cmd::Play{}, cmd::Pause{}, cmd::SetSpeed{2.5}, cmd::SetLoop{false},
      cmd::LoadTf{"preset:filled"}, cmd::SetTolerance{0.1, 0.02},
      cmd::SetMetric{tsp::Metric::perceptual}, cmd::SetCache{true}, cmd::SetPrefetch{false},
      cmd::SetSetting{"upload-budget", "16"}, cmd::SetView{30, -20}, cmd::SetZoom{1.5},
      cmd::SetProjection{true}, cmd::Screenshot{"a.png", false}, cmd::Screenshot{"b.png", true},
      cmd::WaitFrames{4}, cmd::Quit{}};
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(a[i].command == expected[i]) << i;
  EXPECT_EQ(a[0].line, 3);
  EXPECT_EQ(a[17].line, 20);
  EXPECT_TRUE(parse_script("", "empty").empty());
  EXPECT_EQ(commands_of("compositing boxes\nspacing 2.5\npreintegrated on\nquality 1.5\n"
                        "stats s.json\nsampling-tol 0.05\n"),
            (std::vector<Command>{cmd::SetSetting{"compositing", "boxes"},
                                  cmd::SetSetting{"spacing", "2.5"},
                                  cmd::SetSetting{"preintegrated", "on"}, cmd::SetQuality{1.5},
                                  cmd::WriteStats{"s.json"},
                                  cmd::SetSetting{"sampling-tol", "0.05"}}));
  // Every row of the settings table is an action, validated by the table when parsed.
  const auto d = commands_of("span-step mean\nflat slices\nreuse off\ndense off\n"
                             "skip-transparent off\n");
  ASSERT_EQ(d.size(), 5u);
  for (const Command& x : d) EXPECT_TRUE(std::holds_alternative<cmd::SetSetting>(x));
  EXPECT_EQ(std::get<cmd::SetSetting>(d[4]).name, "skip-transparent");
  EXPECT_EQ(commands_of("lod off\ntarget-fps 25\nshow-cut on\nwait-seconds 0.5\nlod-filter fov:2\n"),
            (std::vector<Command>{cmd::SetLod{false}, cmd::SetTargetFps{25}, cmd::ShowCut{true},
                                  cmd::WaitSeconds{0.5}, cmd::SetLodFilter{"fov:2"}}));
  EXPECT_EQ(commands_of("panels off\nevery-step on\nlog-opacity on\nopen a.tsp\n"
                        "open raw.h5 U:mag\nrecord m.mp4\nrecord stop\n"
                        "open u_%04d.raw --raw-dims 8,6,4 --raw-type u8\n"
                        "open m.q Pressure --xyz g.xyz\n"),
            (std::vector<Command>{
                cmd::ShowPanels{false}, cmd::EveryStep{true}, cmd::LogOpacity{true},
                cmd::OpenInput{"a.tsp", "", ""}, cmd::OpenInput{"raw.h5", "U:mag", ""},
                cmd::StartRecording{"m.mp4"}, cmd::StopRecording{},
                cmd::OpenInput{"u_%04d.raw", "", "--raw-dims 8,6,4 --raw-type u8"},
                cmd::OpenInput{"m.q", "Pressure", "--xyz g.xyz"}}));
  EXPECT_EQ(commands_of("probe sphere:1,2,3,4\nprobe-op union\nprobe-surface off\n"
                        "probe-move 1 0.5 0 -2\nprobe-clear\nfield p\n"),
            (std::vector<Command>{cmd::AddProbe{tsp::parse_probe("sphere:1,2,3,4")},
                                  cmd::SetProbeOp{tsp::ProbeOp::unite}, cmd::ProbeSurface{false},
                                  cmd::MoveProbe{1, {0.5, 0, -2}}, cmd::ClearProbes{},
                                  cmd::ShowField{"p"}}));
  EXPECT_EQ(commands_of("reset-camera\nplayback rate\ncapture out\ncapture off\nexpand on\n"
                        "tf-range visible\n"),
            (std::vector<Command>{cmd::ResetCamera{}, cmd::KeepQuality{false}, cmd::Capture{"out"},
                                  cmd::Capture{""}, cmd::ExpandSections{true},
                                  cmd::StretchTf{"visible"}}));
  EXPECT_EQ(commands_of("tf-point move 2 0.25 0.5\ntf-point colour 1 1 0.5 0 0.25\n"
                        "tf-point add 0.75\ntf-point add 0.5 1\ntf-point remove 3\n"),
            (std::vector<Command>{cmd::MoveTfPoint{2, 0.25, 0.5},
                                  cmd::ColourTfPoint{1, {1, 0.5f, 0, 0.25f}},
                                  cmd::AddTfPoint{0.75, std::nullopt}, cmd::AddTfPoint{0.5, 1.0},
                                  cmd::RemoveTfPoint{3}}));
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
  EXPECT_NE(error_of("tf-range file").find("LO:HI with LO < HI (finite), or data, bulk, step or view"), std::string::npos);
  EXPECT_NE(error_of("tf-range 3:1").find("colour range '3:1': expected LO:HI"),
            std::string::npos) << error_of("tf-range 3:1");
  EXPECT_EQ(commands_of("tf-range histogram\ntf-range -1:2\n")[1], Command(cmd::StretchTf{"-1:2"}));
  EXPECT_EQ(commands_of("tf-range step\n")[0], Command(cmd::StretchTf{"step"}));
  EXPECT_NE(error_of("open a.raw U V").find("expected 'open PATH [FIELD] [--OPTION"),
            std::string::npos);
  EXPECT_NE(error_of("panels maybe").find("expected on or off"), std::string::npos);
  EXPECT_NE(error_of("probe cone:1").find("expected plane"), std::string::npos);
  EXPECT_NE(error_of("probe-op xor").find("expected intersect, union or subtract"),
            std::string::npos);
  EXPECT_NE(error_of("probe-move 0 1 2 3").find("not an integer >= 1"), std::string::npos);
  const std::string tf_point_usage =
      "s.txt:1: 'tf-point': expected 'tf-point move N VALUE OPACITY|colour N R G B A|add VALUE "
      "[OPACITY]|remove N'";
  EXPECT_EQ(error_of("tf-point drag 1 2 3"), tf_point_usage);
  EXPECT_EQ(error_of("tf-point move 1 2"), tf_point_usage);
  EXPECT_EQ(error_of("tf-point move 1 0.5 2"), "s.txt:1: tf-point: opacity must be in [0, 1]");
  EXPECT_EQ(error_of("tf-point colour 1 1 1 -1 1"),
            "s.txt:1: tf-point: colour components must be in [0, 1]");
  EXPECT_EQ(error_of("tf-point add inf"), "s.txt:1: tf-point: the value must be finite");
  EXPECT_NE(error_of("tf-point remove 0").find("'0' is not an integer >= 1"), std::string::npos);
}

TEST(PlayerScript, LoadsAFileAndNamesAMissingOne) {
  const auto dir = tsptest::temp_dir();
  std::ofstream(dir / "s.txt") << "step 2\nquit\n";
  const auto a = tspplayer::load_script((dir / "s.txt").string());
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0].command, Command(cmd::GoToStep{2}));
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
  using tspplayer::validate;
  EXPECT_THROW(validate(cmd::SetSpeed{100}), tsp::UsageError);
  EXPECT_NO_THROW(validate(cmd::SetSpeed{5}));
  const std::string from_panel =
      tsptest::error_of<tsp::UsageError>([&] { validate(cmd::SetSetting{"spacing", "0"}); });
  const std::string from_script = tsptest::error_of<tsp::FormatError>(
      [] { tspplayer::parse_script("spacing 0\n", "s.txt"); });
  EXPECT_NE(from_panel, "");
  EXPECT_EQ(from_script, "s.txt:1: " + from_panel);
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
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_EQ(waits_for_frames(a[i].command), expected[i]) << i;
}

}  // namespace

namespace {

// The handshakes with a test driving the window: wait-file with and without its timeout, and
// signal; a wait-file holds the script (a frame passes), a signal does not.
TEST(PlayerScript, WaitFileAndSignalAreHandshakes) {
  EXPECT_EQ(commands_of("wait-file go\nwait-file /tmp/x 5\nsignal ready.txt\n"),
            (std::vector<Command>{cmd::WaitFile{"go", tspplayer::kDefaultWaitFileSeconds},
                                  cmd::WaitFile{"/tmp/x", 5}, cmd::Signal{"ready.txt"}}));
  EXPECT_TRUE(tspplayer::waits_for_frames(cmd::WaitFile{"go", 1}));
  EXPECT_FALSE(tspplayer::waits_for_frames(cmd::Signal{"go"}));
  EXPECT_NE(error_of("wait-file").find("'wait-file' takes a path"), std::string::npos);
  EXPECT_NE(error_of("wait-file a 1 2").find("'wait-file' takes a path"), std::string::npos);
  EXPECT_NE(error_of("wait-file a soon").find("'soon' is not a number"), std::string::npos);
  EXPECT_EQ(error_of("\nwait-file a 601"),
            "s.txt:2: wait-file's timeout must be 0 to 600 seconds");
  EXPECT_NE(error_of("signal").find("'signal' takes 1 argument(s)"), std::string::npos);
}

}  // namespace

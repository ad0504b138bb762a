// The player's typed commands (player/command.h): what keys make is what the equivalent script
// line makes, every action's bad line names the script and the line, and validate() holds
// commands from any source to the script's rules.
#include "player/command.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "player/player_state.h"
#include "player/script.h"
#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"
#include "tsp/metric/tf_io.h"
#include "tsp/metric/transfer_function.h"

namespace {

using tspplayer::Command;
namespace cmd = tspplayer::cmd;

// The command of a one-line script.
Command line_command(const std::string& line) {
  const auto a = tspplayer::parse_script(line + "\n", "k.txt");
  EXPECT_EQ(a.size(), 1u) << line;
  return a.empty() ? Command(cmd::Quit{}) : a[0].command;
}

TEST(PlayerCommand, KeysMakeTheCommandsOfTheirScriptLines) {
  tspplayer::PlayerState s;
  s.step = 3;
  s.playing = false;
  s.show_cut = false;
  s.panels = true;
  s.camera.projection = tsp::Projection::orthographic;
  const int steps = 10;
  const std::pair<int, const char*> keys[] = {
      {GLFW_KEY_SPACE, "play"},         {GLFW_KEY_LEFT, "step 2"},
      {GLFW_KEY_RIGHT, "step 4"},       {GLFW_KEY_HOME, "step 0"},
      {GLFW_KEY_END, "step 9"},         {GLFW_KEY_L, "show-cut on"},
      {GLFW_KEY_R, "reset-camera"},     {GLFW_KEY_TAB, "panels off"},
      {GLFW_KEY_P, "projection persp"}};
  for (const auto& [key, line] : keys) {
    const std::optional<Command> c = tspplayer::key_command(key, s, steps);
    ASSERT_TRUE(c.has_value()) << line;
    EXPECT_TRUE(*c == line_command(line)) << line;
  }
  // The same keys in another state: each toggles back.
  s.playing = true;
  s.show_cut = true;
  s.panels = false;
  s.camera.projection = tsp::Projection::perspective;
  s.step = 9;
  EXPECT_TRUE(*tspplayer::key_command(GLFW_KEY_SPACE, s, steps) == line_command("pause"));
  EXPECT_TRUE(*tspplayer::key_command(GLFW_KEY_L, s, steps) == line_command("show-cut off"));
  EXPECT_TRUE(*tspplayer::key_command(GLFW_KEY_TAB, s, steps) == line_command("panels on"));
  EXPECT_TRUE(*tspplayer::key_command(GLFW_KEY_P, s, steps) == line_command("projection ortho"));
  EXPECT_TRUE(*tspplayer::key_command(GLFW_KEY_RIGHT, s, steps) == line_command("step 9"));
  // S saves the picture (no script line); other keys make nothing.
  EXPECT_TRUE(*tspplayer::key_command(GLFW_KEY_S, s, steps) == Command(cmd::SavePicture{}));
  EXPECT_FALSE(tspplayer::key_command(GLFW_KEY_Q, s, steps).has_value());
  EXPECT_FALSE(tspplayer::key_command(GLFW_KEY_F1, s, steps).has_value());
}

// Every action, given one word too many, is refused with the script's name and line and the
// action named.
TEST(PlayerCommand, EveryActionsBadLineNamesTheLine) {
  const char* const actions[] = {
      "step", "play", "pause", "speed", "loop", "tf", "tf-range", "tolerance", "metric",
      "cache", "prefetch", "view", "zoom", "projection", "screenshot", "screenshot-ui",
      "wait-frames", "wait-seconds", "quality", "stats", "lod", "target-fps", "lod-filter",
      "show-cut", "panels", "every-step", "log-opacity", "open", "field", "probe", "probe-op",
      "probe-surface", "probe-clear", "probe-move", "record", "reset-camera", "playback",
      "capture", "quit", "save-session", "scale", "expand", "spacing", "compositing", "dialog",
      "tf-point", "wait-file", "signal"};
  for (const char* name : actions) {
    const std::string text = std::string("play\n# two\n") + name + " a b c d e f\n";
    const std::string e = tsptest::error_of<tsp::FormatError>(
        [&] { tspplayer::parse_script(text, "bad.txt"); });
    EXPECT_EQ(e.rfind("bad.txt:3: ", 0), 0u) << name << ": " << e;
    EXPECT_NE(e.find(name), std::string::npos) << name << ": " << e;
  }
  // Values out of range: the same line and what is accepted.
  EXPECT_EQ(tsptest::error_of<tsp::FormatError>(
                [] { tspplayer::parse_script("dialog print\n", "bad.txt"); }),
            "bad.txt:1: dialog 'print': expected open, save-tf, record, save-session or close");
  EXPECT_TRUE(tspplayer::parse_script("dialog record\n", "ok.txt")[0].command ==
              Command(cmd::ShowDialog{"record"}));
  EXPECT_EQ(tsptest::error_of<tsp::FormatError>(
                [] { tspplayer::parse_script("\nview 0 95\n", "bad.txt"); }),
            "bad.txt:2: elevation must be in (-90, 90) degrees");
  EXPECT_EQ(tsptest::error_of<tsp::FormatError>(
                [] { tspplayer::parse_script("quit\nfly 1\n", "bad.txt"); })
                .rfind("bad.txt:2: unknown action 'fly': expected step, play,", 0),
            0u);
}

TEST(PlayerCommand, ValidateHoldsEveryCommandToTheScriptsRules) {
  using tspplayer::validate;
  const double inf = std::numeric_limits<double>::infinity();
  const Command bad[] = {cmd::GoToStep{-1},           cmd::SetSpeed{0.1},
                         cmd::SetTolerance{-1, 0},    cmd::SetTolerance{0, inf},
                         cmd::SetView{inf, 0},        cmd::SetView{0, 90},
                         cmd::SetZoom{0},             cmd::WaitFrames{-1},
                         cmd::WaitSeconds{601},       cmd::SetQuality{51},
                         cmd::SetTargetFps{0.5},      cmd::SetLodFilter{"nearest"},
                         cmd::SetScale{{1, 0, 1}},    cmd::MoveProbe{1, {0, inf, 0}},
                         cmd::MoveProbe{0, {0, 0, 0}}, cmd::SetSetting{"spacing", "x"},
                         cmd::SetSetting{"no-such", "1"}, cmd::StretchTf{"3:1"},
                         cmd::MoveTfPoint{0, 0.5, 0.5}, cmd::MoveTfPoint{1, inf, 0.5},
                         cmd::MoveTfPoint{1, 0.5, 1.5}, cmd::ColourTfPoint{1, {2, 0, 0, 1}},
                         cmd::AddTfPoint{0.5, -0.1}, cmd::RemoveTfPoint{0}};
  for (const Command& c : bad) EXPECT_THROW(validate(c), tsp::UsageError) << c.index();
  const Command good[] = {cmd::GoToStep{0},       cmd::SetSpeed{60},
                          cmd::SetTolerance{0, 0}, cmd::SetView{-720, 89.5},
                          cmd::WaitSeconds{0},    cmd::SetLodFilter{"distance:2"},
                          cmd::SetScale{{1, 1, 30}}, cmd::ResetCamera{},
                          cmd::EditProbe{0, {}},  cmd::SetTolerance{0.5, 0.1, false},
                          cmd::MoveTfPoint{1, -3, 1}, cmd::AddTfPoint{2, std::nullopt},
                          cmd::RemoveTfPoint{1}};
  for (const Command& c : good) EXPECT_NO_THROW(validate(c)) << c.index();
  EXPECT_TRUE(tspplayer::waits_for_frames(cmd::Screenshot{"a.png", true}));
  EXPECT_TRUE(tspplayer::waits_for_frames(cmd::WaitFrames{1}));
  EXPECT_FALSE(tspplayer::waits_for_frames(cmd::WaitFrames{0}));
  EXPECT_FALSE(tspplayer::waits_for_frames(cmd::Play{}));
}

// The window's colour range (its field and the script's tf-range) names the control in its
// errors, not play's --tf-range (issue 47 walk 5: typed into the field, "--tf-range '5:1':
// expected auto, data, file, …" named an option the window has not and modes it refuses).
TEST(PlayerCommand, ColourRangeErrorsNameTheControlNotTheOption) {
  for (const char* bad : {"5:1", "abc", "file", "1:inf"}) {
    const std::string e = tsptest::error_of<tsp::UsageError>(
        [&] { tspplayer::validate(cmd::StretchTf{bad}); });
    EXPECT_EQ(e, std::string("colour range '") + bad +
                     "': expected LO:HI with LO < HI (finite), or data, bulk, step or view");
  }
  EXPECT_EQ(tsptest::error_of<tsp::FormatError>(
                [] { tspplayer::parse_script("tf-range 2:1\n", "r.txt"); }),
            "r.txt:1: colour range '2:1': expected LO:HI with LO < HI (finite), or data, "
            "bulk, step or view");
  // A loaded map that misses the data says what in the window stretches it.
  const std::vector<tsp::TfPoint> points = {{5, {1, 1, 1, 1}}, {6, {1, 1, 1, 1}}};
  const tsp::TransferFunction tf = tsp::TransferFunction::from_points({5, 6}, points, 16);
  EXPECT_NE(tsp::tf_range_warning(tf, {0, 1}, "fit to data").find("nothing will show; fit to data"),
            std::string::npos);
}

}  // namespace

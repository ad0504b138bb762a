// What the window player's tests share (tests/player/player*_test.cpp): the picture size and ΔE
// bounds they compare with, a small .tsp, scripts for --script and for bash (xdotool), and
// `tspplay render` of one step to compare a screenshot with.
#pragma once
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/paths.h"
#include "tsp/report/image.h"

namespace tsptest::player {

/// The window and render size the player tests use.
inline constexpr const char* kSize = "128x96";
/// Same view, TF and metric as `render`'s defaults: frames match up to blending noise.
inline constexpr double kSameFrameDeltaE = 0.5;
/// Above this, two frames differ.
inline constexpr double kDifferentFrameDeltaE = 1.0;

/// True when a GLFW window can be opened (a display is there).
bool window_possible();
/// Writes a bash script (the player in the background, xdotool driving it) and runs it on an X
/// server of its own (Xvfb: no other test's window takes the focus or covers the player's);
/// returns its exit status.
int run_bash(const std::filesystem::path& script, const std::string& text);
/// A 30×28×26 × 4-step shock built into a .tsp with bricks of 16 (in a fresh temporary folder).
std::filesystem::path make_tsp();
/// Writes a --script file (in a fresh temporary folder) and returns its path.
std::filesystem::path write_script(const std::string& text);
/// Share of pixels that are not the black background.
double covered(const tsp::Image& im);
/// `tspplay render` of one step at kSize with TF tf.
tsp::Image render_step(const std::filesystem::path& tsp, int step,
                       const std::string& tf = "preset:auto");
/// A whole text file.
std::string read_text(const std::filesystem::path& p);
/// A JSON file (stats, frames.json).
nlohmann::json read_json(const std::filesystem::path& p);
/// The labels the last frame drew (a `stats` file's ui_items) that contain text.
std::vector<std::string> labels_with(const nlohmann::json& stats, const std::string& text);
/// A script that orbits at a target no software renderer reaches (stats in dir/moving.json),
/// then stops and waits (dir/idle.json) and takes a screenshot, which waits for full quality.
std::string orbit_then_idle_script(const std::filesystem::path& dir,
                                   const std::filesystem::path& shot);

/// Bash functions over a player's output file `log`, for scripts that drive a window with
/// xdotool and wait on --trace lines, not on the clock: `until_log TEXT` waits for a line with
/// TEXT, `until_n TEXT N` for N of them, `until_file PATH` for a file (a minute at most each;
/// when one never comes it says so, ends the player started last with & and exits 1);
/// `quit_player` sends Ctrl+Q to window $w and returns the player's exit status, releasing Ctrl
/// and Q.
std::string log_waits(const std::filesystem::path& log);

/// Bash lines for after log_waits, with the traced player's window in $w: Ctrl+O opens File >
/// Open, "abc" is typed into its path field, Ctrl+A selects it all and "x" replaces it, each
/// step waited on through --trace lines.
std::string select_all_in_open_dialog();
/// A bash function for after log_waits: `handshake NAME` makes dir/NAME.sent once the test's
/// input before it is sent, and waits for the player's dir/NAME.taken (the script's taken(dir,
/// NAME) lines: every window event sent before it taken and settled).
std::string handshakes(const std::filesystem::path& dir);
/// Script lines that wait for the test's `handshake NAME` (wait-file dir/NAME.sent) and then
/// tell it so (signal dir/NAME.taken).
std::string taken(const std::filesystem::path& dir, const std::string& name);
/// The script of a test that ends the player with Ctrl+Q (quit_player): nothing to do but wait,
/// and a run whose Ctrl+Q never came fails (after 300 s, naming the line) rather than quitting.
std::string until_ctrl_q(const std::filesystem::path& dir);
/// Expects the log of select_all_in_open_dialog's keys: "abc" typed, then replaced whole by "x"
/// (without the select-all the x went after it: "abcx").
void expect_select_all_replaced(const std::string& log);

}  // namespace tsptest::player

/// The start of a test that drives a window with real X events (xdotool): a display, as
/// TSPTEST_REQUIRE asks for one, and xdotool, whose absence fails the test
/// (scripts/install-deps.sh installs it).
#define TSPTEST_REQUIRE_X_EVENTS()                                                          \
  do {                                                                                      \
    TSPTEST_REQUIRE(tsptest::player::window_possible(), "no display (run under xvfb-run)"); \
    ASSERT_EQ(std::system("command -v xdotool > /dev/null"), 0)                             \
        << "xdotool missing (scripts/install-deps.sh installs it)";                         \
  } while (0)

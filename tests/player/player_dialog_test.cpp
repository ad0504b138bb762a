// File > Open as a scientist uses it, under real X events (xdotool) at the window's normal frame
// rate (issue 47's fresh-eye walk; frames of 80 ms, as llvmpipe draws a large window): a quick Ctrl+A selects the path, Escape closes the dialog,
// Enter in the path field opens the file, and a double-click on a folder enters that folder, not
// the one under the mouse in it. Each step waits on the player's --trace lines, not on the clock.
// (Helpers: support/player_run.h.)
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "support/paths.h"
#include "support/player_run.h"

namespace {

namespace fs = std::filesystem;
using tsptest::q;
using namespace tsptest::player;

TEST(Player, OpenDialogTakesCtrlAEscapeEnterAndDoubleClicksAsExpected) {
  TSPTEST_REQUIRE_X_EVENTS();
  const fs::path dir = tsptest::temp_dir(), out = dir / "keys.out", tsp = dir / "s.tsp";
  fs::copy_file(make_tsp(), tsp);
  fs::create_directories(dir / "a" / "b" / "c");
  const fs::path other = dir / "a" / "o.tsp";
  fs::copy_file(tsp, other);
  const fs::path backstop = write_script(until_ctrl_q(dir));
  const std::string cmd =
      log_waits(out) + "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) + " --size 640x480 --cache-dir " +
      q(dir / "cache") + " --trace --frame-delay-ms 80 --script " + q(backstop) + " > " + q(out) + " 2>&1 &\n" +
      "w=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n"
      "until_log 'trace: tf canvas'\n"
      // Idle, the window wakes on Ctrl's press and draws a frame with Ctrl alone; A's press and
      // Ctrl's release (xdotool releases in the order it pressed, 20 ms apart) come during it,
      // so the next frame's queue holds both. A tap that arrives as a plain A shows below (abcx,
      // or an a typed).
      + select_all_in_open_dialog() +
      "xdotool key --window \"$w\" Escape\n"
      "until_log 'trace: open dialog closed'\n"
      "xdotool key --window \"$w\" ctrl+o\n"
      "until_n 'trace: open path field active' 2\n"
      // The field opens with its folder selected: End, then the file's name in it.
      "xdotool key --window \"$w\" End\n"
      "xdotool type --window \"$w\" a/o.tsp\n"
      "until_log " + q("trace: open path " + other.string() + "$") + "\n"
      "xdotool key --window \"$w\" Return\n"
      "until_log " + q("opened " + other.string()) + "\n"
      // Opened again, the dialog lists a/ (where the last file came from): ../ b/ o.tsp. A
      // double-click on b/ enters b/, whose second row (c/) is then under the mouse.
      "xdotool key --window \"$w\" ctrl+o\n"
      "until_n 'trace: open path field active' 3\n"
      "read x y h <<< \"$(grep 'trace: open list' " + q(out) + " | tail -1 | cut -d' ' -f4-)\"\n"
      "xdotool mousemove --window \"$w\" $((x + 30)) $((y + h + h / 2)) click --repeat 2 --delay 80 1\n"
      "until_log " + q("trace: open folder " + (dir / "a" / "b").string() + "$") + "\n"
      "xdotool key --window \"$w\" Escape\n"
      "until_n 'trace: open dialog closed' 2\n"
      "quit_player)\n";
  ASSERT_EQ(run_bash(dir / "keys.sh", cmd), 0) << tsptest::read_file(out);
  const std::string log = tsptest::read_file(out);
  // Ctrl+A replaced "abc" whole: without it (a plain A) the x went after "abc".
  expect_select_all_replaced(log);
  // Enter opened the typed file (a .tsp: at once).
  EXPECT_NE(log.find("trace: open dialog opens " + other.string() + "\n"), std::string::npos) << log;
  // The double-click went one level down, not two.
  EXPECT_EQ(log.find("open folder " + (dir / "a" / "b" / "c").string()), std::string::npos) << log;
}

}  // namespace

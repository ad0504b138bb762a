// Issue 47's eighth fresh-eye walk: each finding reproduced by a small window (scripted, or
// driven by xdotool and waited on through --trace lines) that failed before its fix.
// (Helpers: support/player_run.h.)
#include <gtest/gtest.h>

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

}  // namespace

// Inputs played without --field name the field their reader picked (issue 47's fresh-eye walk:
// the hot plume and the dam break played untitled legends, and S saved NAME__step_….png): the
// build records it, so the window's field, the legend, S's file names and movies carry it.
// (Helpers: support/player_run.h.)
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "support/paths.h"
#include "support/player_run.h"
#include "tsp/store/tsp_file.h"

namespace {

namespace fs = std::filesystem;
using tsptest::q;
using tsptest::run_tspplay;
using namespace tsptest::player;

// build without --field records the reader's pick: an HDF5 file's only dataset, a mesh's array.
TEST(Player, BuildWithoutFieldRecordsTheFieldItPicked) {
  const fs::path dir = tsptest::temp_dir();
  const fs::path plume = tsptest::datasets_dir() / "samples" / "hotPlume_32.h5";
  auto r = run_tspplay("build " + q(plume) + " -o " + q(dir / "p.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(tsp::TspFile::open((dir / "p.tsp").string())->fields(), std::vector<std::string>{"T"});
  const fs::path dam =
      tsptest::datasets_dir() / "samples/damBreakWithObstacle/damBreakWithObstacle.vtu.series";
  r = run_tspplay("build " + q(dam) + " --resolution 16 -o " + q(dir / "d.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> fields = tsp::TspFile::open((dir / "d.tsp").string())->fields();
  ASSERT_EQ(fields.size(), 1u);
  EXPECT_FALSE(fields[0].empty());
  // Named, the name given is recorded.
  r = run_tspplay("build " + q(plume) + " --field T -o " + q(dir / "n.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(tsp::TspFile::open((dir / "n.tsp").string())->fields(), std::vector<std::string>{"T"});
}

// play without --field: the window's field (stats) is the picked one, and S (a real X key
// event) saves NAME_FIELD_step_NNNN.png, not NAME__step_NNNN.png.
TEST(Player, PlayWithoutFieldNamesThePickedFieldInStatsAndSavedFiles) {
  TSPTEST_REQUIRE_X_EVENTS();
  const fs::path dir = tsptest::temp_dir(), out = dir / "play.out";
  // (A copy: S saves beside the data, not in the source tree.)
  const fs::path plume = dir / "hotPlume_32.h5";
  fs::copy_file(tsptest::datasets_dir() / "samples" / "hotPlume_32.h5", plume);
  const fs::path script = write_script("wait-frames 2\nstats " + (dir / "s.json").string() +
                                       "\n" + until_ctrl_q(dir));
  const std::string cmd =
      "cd " + q(dir) + " && (" + q(tsptest::tspplay_bin()) + " play " + q(plume) + " --size " +
      kSize + " --cache-dir " + q(dir / "cache") + " --trace --script " + q(script) + " > " +
      q(out) + " 2>&1 &\n" + "w=$(xdotool search --sync --name " + q("tspplay - " + plume.string()) +
      " | head -1)\n"
      "for i in $(seq 600); do [ -f s.json ] && break; sleep 0.1; done\n"
      "xdotool key --window \"$w\" s\n"
      "for i in $(seq 600); do ls hotPlume_32_*.png > /dev/null 2>&1 && break; sleep 0.1; done\n"
      "xdotool key --window \"$w\" ctrl+q\n"
      // xdotool sends to the focused window through XTEST; once Ctrl+Q has closed it, Q's
      // release fails and Q stays down on the display, repeating into the next test's window.
      "wait; rc=$?; xdotool keyup ctrl q; exit $rc)\n";
  ASSERT_EQ(run_bash(dir / "s.sh", cmd), 0) << tsptest::read_file(out);
  EXPECT_EQ(read_json(dir / "s.json")["field"], "T");
  EXPECT_TRUE(fs::exists(dir / "hotPlume_32_T_step_0000.png")) << tsptest::read_file(out);
  EXPECT_FALSE(fs::exists(dir / "hotPlume_32__step_0000.png"));
}

}  // namespace

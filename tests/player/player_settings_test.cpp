// The player's settings commands (script lines and panel widgets send the same set command):
// a knob that excludes another turns it off and says so, never a silent override while drawing.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "support/paths.h"
#include "support/player_run.h"

namespace {

namespace fs = std::filesystem;
using tsptest::q;
using tsptest::run_tspplay;
using namespace tsptest::player;

TEST(PlayerSettings, TheSamplingKnobJustSetWinsAndTheStatusSaysWhatWentOff) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string a = (dir / "a.json").string(), b = (dir / "b.json").string(),
                    c = (dir / "c.json").string();
  const auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " +
                             q(write_script("sampling-tol 0.5\nwait-frames 1\nstats " + a +
                                            "\npreintegrated on\nwait-frames 1\nstats " + b +
                                            "\nsampling-tol 0.25\nwait-frames 1\nstats " + c +
                                            "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json ja = read_json(a), jb = read_json(b), jc = read_json(c);
  EXPECT_EQ(ja["sampling_tol"], 0.5);
  EXPECT_EQ(ja["preintegrated"], false);
  // Pre-integration asked for: adaptive sampling goes off, and the status says so.
  EXPECT_EQ(jb["preintegrated"], true);
  EXPECT_EQ(jb["sampling_tol"], 0);
  EXPECT_NE(jb["status"].get<std::string>().find("adaptive sampling turned off"),
            std::string::npos)
      << jb["status"];
  // And back: adaptive sampling asked for turns pre-integration off.
  EXPECT_EQ(jc["sampling_tol"], 0.25);
  EXPECT_EQ(jc["preintegrated"], false);
  EXPECT_NE(jc["status"].get<std::string>().find("pre-integration turned off"),
            std::string::npos)
      << jc["status"];
}

// File > Open of another input while the mesh's boundary is drawn: the old mesh is not drawn
// over the new file (it once was, and refining bands over it failed an assertion or crashed);
// the surface control reads the opened input's boundary when it is a mesh, else says what it
// needs and goes off.
TEST(PlayerSettings, OpeningAnotherInputTakesTheOldMeshsSurfaceAway) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string mesh = (tsptest::test_data_dir() / "vtu" / "binary_%d.vtu").string();
  const std::string a = (dir / "a.json").string(), b = (dir / "b.json").string();
  const auto r = run_tspplay(
      "play " + q(mesh) + " --field f --resolution 32 --surface boundary --size " + kSize +
      " --script " +
      q(write_script("wait-frames 2\nstats " + a + "\nopen " + tsp.string() +
                     "\nwait-frames 4\nstats " + b + "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json ja = read_json(a), jb = read_json(b);
  EXPECT_EQ(ja["surface"], "boundary") << ja["status"];
  EXPECT_EQ(jb["surface"], "off");
  EXPECT_EQ(jb["surface_mesh"], "");
  // (The file opened is a grid's: the message says so, not "the mesh it was built from".)
  EXPECT_NE(jb["status"].get<std::string>().find("this input is a grid"), std::string::npos)
      << jb["status"];
}

// Turning the boundary off says so: the status line that named the boundary drawn stayed on
// screen after it was gone (the eighth walk).
TEST(PlayerSettings, TurningTheSurfaceOffSaysSo) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir();
  const std::string mesh = (tsptest::test_data_dir() / "vtu" / "binary_%d.vtu").string();
  const std::string a = (dir / "a.json").string(), b = (dir / "b.json").string();
  const auto r = run_tspplay(
      "play " + q(mesh) + " --field f --resolution 32 --size " + kSize + " --script " +
      q(write_script("wait-frames 2\nsurface boundary\nwait-frames 2\nstats " + a +
                     "\nsurface off\nwait-frames 2\nstats " + b + "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json ja = read_json(a), jb = read_json(b);
  EXPECT_NE(ja["status"].get<std::string>().find("surface: the boundary of"), std::string::npos)
      << ja["status"];
  EXPECT_EQ(jb["surface"], "off");
  EXPECT_EQ(jb["status"], "surface off");
}

}  // namespace

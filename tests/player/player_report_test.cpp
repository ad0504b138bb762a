// The same frame reported by `tspplay render` (frames.json) and by the window (the script's
// `stats`, its frame_report) under the same keys: both writers go through FrameReport's one
// to_json (docs/formats.md, "Reports"). (Helpers: support/player_run.h.)
#include <gtest/gtest.h>

#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "render/frame_report.h"
#include "support/paths.h"
#include "support/player_run.h"

namespace {

namespace fs = std::filesystem;
using namespace tsptest::player;
using tsptest::q;
using tsptest::run_tspplay;

std::set<std::string> keys(const nlohmann::json& j) {
  std::set<std::string> k;
  for (const auto& [key, value] : j.items()) k.insert(key);
  return k;
}

TEST(PlayerReport, StatsAndFramesJsonShareTheFrameKeys) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  // Full quality, as render draws it (no LOD cut, no quality rung), on the GL caster both times.
  const fs::path script = write_script("lod off\nquality 0\nbackend gl\nwait-frames 3\nstats " +
                                       (dir / "s.json").string() + "\nquit\n");
  auto p = run_tspplay("play " + q(tsp) + " --no-session --size " + kSize + " --script " +
                       q(script));
  ASSERT_EQ(p.exit_code, 0) << p.err;
  auto r = run_tspplay("render " + q(tsp) + " --steps 0 --backend gl --size " +
                       std::string(kSize) + " -o " + q(dir / "r"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json stats = read_json(dir / "s.json");
  const nlohmann::json frame = read_json(dir / "r" / "frames.json").at("frames").at(0);
  ASSERT_TRUE(stats.contains("frame_report")) << stats.dump(1);
  const nlohmann::json& shown = stats["frame_report"];
  // Exactly FrameReport's keys in stats, and every one of them in frames.json's record.
  EXPECT_EQ(keys(shown), keys(nlohmann::json(tspgl::FrameReport{})));
  for (const std::string& k : keys(shown)) EXPECT_TRUE(frame.contains(k)) << k;
  // The same frame (step 0, its view and knobs): what does not depend on the clock agrees.
  for (const char* k : {"step", "caster", "steps_merged", "steps_shown", "dense", "not_rendered",
                        "untextured", "clipped"})
    EXPECT_EQ(shown.at(k), frame.at(k)) << k;
  // The names the window used to write by hand are gone (one key per field).
  for (const char* k : {"render_ms", "classes", "caster", "fragments", "deferred_textures"})
    EXPECT_FALSE(stats.contains(k)) << k;
}

}  // namespace

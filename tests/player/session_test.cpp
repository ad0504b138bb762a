// The player's session file (issue 47 item 4) without a window: every member round-trips exactly
// through JSON and through a file; another version, a wrong type or an out-of-range value is a
// FormatError naming the file; the cache entry is keyed by the input as named and the field.
#include "player/session.h"

#include "player/script.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"

namespace {

namespace fs = std::filesystem;
using tspplayer::Session;

Session full_session() {
  Session s;
  s.input = "/data/run.h5";
  s.field = "T";
  s.tf_domain = {-1.5, 2.25};
  s.tf_entries = {{0, 0, 0, 0}, {0.1f, 0.2f, 0.3f, 0.4f}, {1, 1, 1, 1}};
  s.tf_points = {{-1.5, {0, 0, 0, 0}}, {0.125, {0.5f, 0.25f, 1, 0.75f}}, {2.25, {1, 1, 1, 1}}};
  s.tf_label = "edited";
  s.log_opacity = true;
  s.azimuth_deg = 123.456789012345;
  s.elevation_deg = -33.3;
  s.zoom = 2.5;
  s.fov_deg = 45;
  s.perspective = true;
  s.pan = {0.1, -0.2};
  s.eye = std::array<double, 3>{1, 2, 3};
  s.scale = {1, 1, 30};
  s.step = 3;
  s.speed = 2.5;
  s.loop = false;
  s.every_step = false;
  s.probes = {"plane:0,0,1,10", "sphere:5,5,5,2"};
  s.probe_op = "union";
  s.probe_surface = false;
  s.surface = true;
  s.panels = false;
  s.annotations = false;
  s.ui_ini = "[Window][Settings]\nPos=10,20\nCollapsed=0\n";
  s.ui_open = {{"##side", {{3141592653ll, 0}, {42, 1}}}};
  return s;
}

std::string error_of(const nlohmann::json& j) {
  return tsptest::error_of<tsp::FormatError>(
      [&] { tspplayer::session_from_json(j, "state.json"); });
}

TEST(PlayerSession, EveryMemberRoundTripsThroughJson) {
  const Session s = full_session();
  EXPECT_EQ(tspplayer::session_from_json(to_json(s), "x"), s);
  // And the defaults (no TF kept, the orbit camera without an eye).
  EXPECT_EQ(tspplayer::session_from_json(to_json(Session{}), "x"), Session{});
  EXPECT_EQ(to_json(s)["version"], tspplayer::kSessionVersion);
  // A member left out keeps the player's default.
  Session partial = tspplayer::session_from_json({{"version", tspplayer::kSessionVersion}, {"speed", 4}}, "x");
  Session expected;
  expected.speed = 4;
  EXPECT_EQ(partial, expected);
}

TEST(PlayerSession, RoundTripsThroughAFileWrittenAtomically) {
  const fs::path dir = tsptest::temp_dir();
  const std::string path = tspplayer::session_cache_path("run.h5", "T", dir.string());
  ASSERT_FALSE(path.empty());
  EXPECT_EQ(fs::path(path).parent_path(), dir / "sessions");
  tspplayer::write_session(path, full_session(), true);  // makes its folder
  EXPECT_EQ(tspplayer::read_session(path), full_session());
  int files = 0;  // no temporary left beside it
  for (const auto& e : fs::directory_iterator(dir / "sessions")) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
  // A link planted at a cache entry's name is replaced, its target untouched.
  const fs::path target = dir / "target.txt";
  std::ofstream(target) << "keep";
  fs::remove(path);
  fs::create_symlink(target, path);
  tspplayer::write_session(path, full_session(), true);
  EXPECT_FALSE(fs::is_symlink(path));
  EXPECT_EQ(tsptest::read_file(target), "keep");
}

TEST(PlayerSession, CacheEntryIsKeyedByTheInputAsNamedAndTheField) {
  const std::string dir = tsptest::temp_dir().string();
  const std::string a = tspplayer::session_cache_path("/d/run.h5", "T", dir);
  EXPECT_EQ(a, tspplayer::session_cache_path("/d/./x/../run.h5", "T", dir));
  EXPECT_NE(a, tspplayer::session_cache_path("/d/run.h5", "W", dir));
  EXPECT_NE(a, tspplayer::session_cache_path("/d/run2.h5", "T", dir));
  // A relative name is the file in the working directory.
  EXPECT_EQ(tspplayer::session_cache_path("run.h5", "", dir),
            tspplayer::session_cache_path((fs::current_path() / "run.h5").string(), "", dir));
  EXPECT_EQ(tspplayer::session_cache_path("/d/run.h5", "T", "-"), "");  // no cache folder
}

TEST(PlayerSession, ForeignOrBadFilesAreFormatErrorsNamingTheFile) {
  const int v = tspplayer::kSessionVersion;
  EXPECT_EQ(error_of(nlohmann::json::array()),
            "state.json: not a tspplay session (not a JSON object)");
  EXPECT_EQ(error_of({{"speed", 2}}), "state.json: not a tspplay session (no version)");
  EXPECT_EQ(error_of({{"version", v + 1}}),
            "state.json: session version " + std::to_string(v + 1) + ", this tspplay reads version " +
                std::to_string(v));
  EXPECT_NE(error_of({{"version", v}, {"speed", "fast"}}).find("state.json: session key 'speed'"),
            std::string::npos);
  EXPECT_EQ(error_of({{"version", v}, {"camera", {{"zoom", -1}}}}),
            "state.json: session key 'camera.zoom': expected a positive number");
  EXPECT_EQ(error_of({{"version", v}, {"camera", {{"elevation_deg", 90}}}}),
            "state.json: session key 'camera.elevation_deg': expected (-90, 90)");
  EXPECT_EQ(error_of({{"version", v}, {"scale", {1, 0, 1}}}),
            "state.json: session key 'scale': expected three positive factors");
  EXPECT_EQ(error_of({{"version", v}, {"tf", {{"domain", {2, 1}}}}}),
            "state.json: session key 'tf.domain': expected lo < hi");
  EXPECT_EQ(error_of({{"version", v}, {"tf", {{"entries", {{0, 0, 0, 2}, {0, 0, 0, 0}}}}}}),
            "state.json: session key 'tf': colour components lie in [0, 1]");
  EXPECT_EQ(error_of({{"version", v}, {"panels", {{"open", {{"w", {{1, 7}}}}}}}}),
            "state.json: session key 'panels.open': expected [id, 0|1]");
  // A file that is not JSON, or missing: named.
  const fs::path bad = tsptest::temp_dir() / "bad.json";
  std::ofstream(bad) << "{ not json";
  EXPECT_NE(tsptest::error_of<tsp::FormatError>([&] { tspplayer::read_session(bad.string()); })
                .find(bad.string()),
            std::string::npos);
  EXPECT_NE(tsptest::error_of<tsp::IoError>(
                [&] { tspplayer::read_session((bad.parent_path() / "none.json").string()); })
                .find("none.json"),
            std::string::npos);
}

// The script's session and axis-scale actions (save-session PATH, scale SX,SY,SZ).
TEST(PlayerSession, ScriptSavesSessionsAndScalesAxes) {
  const auto a = tspplayer::parse_script("save-session /tmp/s.json\nscale 1,1,2.5\n", "s.txt");
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0].command, tspplayer::Command(tspplayer::cmd::SaveSession{"/tmp/s.json"}));
  EXPECT_EQ(a[1].command, tspplayer::Command(tspplayer::cmd::SetScale{{1, 1, 2.5}}));
  auto error = [](const std::string& text) {
    return tsptest::error_of<tsp::FormatError>([&] { tspplayer::parse_script(text, "s.txt"); });
  };
  EXPECT_EQ(error("scale 1,2\n"), "s.txt:1: '1,2': expected SX,SY,SZ");
  EXPECT_EQ(error("scale 1,2,3,4\n"), "s.txt:1: '1,2,3,4': expected SX,SY,SZ");
  EXPECT_EQ(error("scale 1,0,3\n"), "s.txt:1: scale: expected three factors in (0, 1000]");
  EXPECT_EQ(error("scale 1,x,3\n"), "s.txt:1: 'x' is not a number (expected 'scale SX,SY,SZ')");
  EXPECT_EQ(error("save-session\n"),
            "s.txt:1: 'save-session' takes 1 argument(s): expected 'save-session PATH', found 0");
}

}  // namespace

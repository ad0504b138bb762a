// `render --backend auto|gl|cpu` and `--render-scale S` end to end: frames.json names who drew
// each frame, a combination the CPU caster cannot draw is drawn by GL with a note, the two back
// ends draw the same picture, a bad word is a usage error, and a half render scale draws a
// picture close to the full one.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/json_file.h"
#include "support/paths.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tsptest::quote;
using tsptest::run_tspplay;

class BackendCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(tsptest::temp_dir());
    ASSERT_EQ(run_tspplay("generate shock -o " + quote(*dir_ / "s.h5") + " --dims 32 --steps 3")
                  .exit_code, 0);
    ASSERT_EQ(run_tspplay("build " + quote(*dir_ / "s.h5") + " --field shock --brick 8 -o " +
                          quote(*dir_ / "s.tsp"))
                  .exit_code, 0);
  }
  static void TearDownTestSuite() { delete dir_; }
  static inline fs::path* dir_ = nullptr;

  // Renders step 1 at 160x120 with `options` into a fresh folder; returns its frames.json.
  static json render(const std::string& options, const fs::path& out) {
    const auto r = run_tspplay("render " + quote(*dir_ / "s.tsp") +
                               " --steps 1:1 --size 160x120 " + options + " -o " + quote(out));
    EXPECT_EQ(r.exit_code, 0) << options << "\n" << r.err;
    return tsptest::frames_json(out);
  }
  static const json& frame(const json& j) { return j.contains("frames") ? j["frames"][0] : j[0]; }
};

TEST_F(BackendCli, FramesSayWhoDrewThemAndTheBackEndsAgree) {
  const fs::path cpu = *dir_ / "cpu", gl = *dir_ / "gl";
  EXPECT_EQ(frame(render("--backend cpu", cpu))["caster"], "cpu");
  EXPECT_GT(frame(render("--backend cpu", cpu))["samples"].get<long long>(), 0);
  EXPECT_EQ(frame(render("--backend gl", gl))["caster"], "gl");
  const tsp::DiffStats d = tsp::diff_images(tsp::read_png((cpu / "step_0001.png").string()),
                                            tsp::read_png((gl / "step_0001.png").string()));
  EXPECT_LT(d.mean, 0.05);
  EXPECT_LT(d.p99, 1.0);
}

TEST_F(BackendCli, WhatTheCpuCasterCannotDrawIsDrawnByGlWithANote) {
  const auto r = run_tspplay("render " + quote(*dir_ / "s.tsp") +
                             " --steps 1:2 --size 160x120 --backend cpu --preintegrated on -o " +
                             quote(*dir_ / "pre_warn"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string note = "the cpu caster does not draw pre-integration: drawn by gl";
  const std::size_t at = r.err.find(note);
  EXPECT_NE(at, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(note, at + 1), std::string::npos) << "said once: " << r.err;
  const json j = render("--backend cpu --preintegrated on", *dir_ / "pre");
  EXPECT_EQ(frame(j)["caster"], "gl");
  EXPECT_NE(frame(j)["caster_note"].get<std::string>().find("pre-integration"), std::string::npos)
      << frame(j);
}

TEST_F(BackendCli, ABadBackendIsAUsageError) {
  const auto r = run_tspplay("render " + quote(*dir_ / "s.tsp") + " --backend vulkan -o " +
                             quote(*dir_ / "bad"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--backend"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(*dir_ / "bad"));
}

TEST_F(BackendCli, HalfTheRaysDrawAPictureCloseToTheFullOne) {
  const fs::path full = *dir_ / "full", half = *dir_ / "half";
  render("--backend cpu", full);
  render("--backend cpu --render-scale 0.5", half);
  const tsp::Image a = tsp::read_png((full / "step_0001.png").string());
  const tsp::Image b = tsp::read_png((half / "step_0001.png").string());
  ASSERT_EQ(a.width, b.width);
  const tsp::DiffStats d = tsp::diff_images(a, b);
  EXPECT_GT(d.max, 0.0);  // not the same rays
  EXPECT_LT(d.mean, 2.0);
  const auto r = run_tspplay("render " + quote(*dir_ / "s.tsp") + " --render-scale 0.1 -o " +
                             quote(*dir_ / "bad_scale"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--render-scale"), std::string::npos) << r.err;
}

TEST_F(BackendCli, ThePlayerSwitchesCastersByScriptAndSaysWhoDrew) {
  TSPTEST_REQUIRE(std::getenv("DISPLAY"), "no display (scripts/test.sh runs the suite under Xvfb)");
  const fs::path script = *dir_ / "backend.txt";
  std::ofstream(script) << "backend gl\nwait-frames 2\nstats " << (*dir_ / "gl.json").string()
                        << "\nbackend cpu\nwait-frames 2\nstats " << (*dir_ / "cpu.json").string()
                        << "\nquit\n";
  const auto r = run_tspplay("play " + quote(*dir_ / "s.tsp") + " --size 320x240 --script " +
                             quote(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* who : {"gl", "cpu"}) {
    const json j = tsptest::read_json(*dir_ / (std::string(who) + ".json"));
    EXPECT_EQ(j["backend"], who);
    EXPECT_EQ(j["frame_report"]["caster"], who);
  }
}

}  // namespace

// render --gl (issue 45 item 1): the same frames through EGL (Mesa's software device here) and
// through OSMesa are the same bytes, on the GL caster and on the CPU caster; frames.json names
// the context, vendor and renderer; an EGL request that cannot be served falls back with one
// warning line and still renders.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "gl/headless.h"
#include "support/json_file.h"
#include "support/paths.h"

namespace {

namespace fs = std::filesystem;
using tsptest::frames_json;
using tsptest::quote;
using tsptest::run_tspplay;

struct EglCli : ::testing::Test {
  fs::path dir = tsptest::temp_dir();
  void SetUp() override {
    ASSERT_EQ(run_tspplay("generate shock -o " + quote(dir / "s.h5") + " --dims 20 --steps 3")
                  .exit_code, 0);
    ASSERT_EQ(run_tspplay("build " + quote(dir / "s.h5") + " -o " + quote(dir / "s.tsp")).exit_code,
              0);
  }
  tsptest::RunResult render(const std::string& out, const std::string& extra) {
    return run_tspplay("render " + quote(dir / "s.tsp") + " --size 96x72 --tf preset:filled " +
                       extra + " -o " + quote(dir / out));
  }
};

TEST_F(EglCli, EglAndOsmesaDrawTheSameBytesOnEitherCaster) {
  TSPTEST_REQUIRE(!tspgl::egl_devices().empty(), "EGL enumerates no device (libegl-mesa0)");
  for (const char* backend : {"gl", "cpu"}) {
    const std::string e = std::string("egl_") + backend, o = std::string("osm_") + backend;
    auto a = render(e, std::string("--gl egl --backend ") + backend);
    ASSERT_EQ(a.exit_code, 0) << a.err;
    EXPECT_EQ(a.err.find("warning"), std::string::npos) << a.err;
    auto b = render(o, std::string("--gl osmesa --backend ") + backend);
    ASSERT_EQ(b.exit_code, 0) << b.err;
    for (const char* png : {"step_0000.png", "step_0001.png", "step_0002.png"})
      EXPECT_EQ(tsptest::read_file(dir / e / png), tsptest::read_file(dir / o / png))
          << backend << " " << png;
    const auto je = frames_json(dir / e), jo = frames_json(dir / o);
    EXPECT_EQ(je["context"].get<std::string>().rfind("EGL device ", 0), 0u) << je["context"];
    EXPECT_EQ(jo["context"], "OSMesa");
    EXPECT_FALSE(je["gl_vendor"].get<std::string>().empty());
    EXPECT_EQ(je["renderer"], jo["renderer"]);  // llvmpipe behind both
  }
}

TEST_F(EglCli, AnEglRequestThatCannotBeServedFallsBackWithOneLine) {
  auto r = render("f", "--gl egl --gpu 15");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("EGL device 15 does not exist"), std::string::npos) << r.err;
  EXPECT_EQ(frames_json(dir / "f")["context"], "OSMesa");
  auto bad = render("g", "--gl vulkan");
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--gl vulkan: expected auto, egl or osmesa"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "g"));
}

}  // namespace

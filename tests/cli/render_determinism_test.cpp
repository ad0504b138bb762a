// The same render command draws the same bytes (issue 44 item 1): twice in a row on both back
// ends, with partial-image reuse, an LOD level and a clip probe; and a step's picture does not
// depend on the steps drawn before it (what tspplay-mpi render's ranks and bench's re-rendered
// rows rely on). A refined run that closed at a brick whose neighbour was empty or flat used to
// read its last sample through that neighbour's page, i.e. from wherever the atlas held
// something: one pixel off by ΔE 52 when step 4 followed steps 0–3 instead of step 3 alone.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/json_file.h"
#include "support/paths.h"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using tsptest::q;
using tsptest::run_tspplay;

class RenderDeterminism : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(tsptest::temp_dir());
    // Bricks of 8 samples over 32³: many brick faces beside empty and flat bricks.
    ASSERT_EQ(run_tspplay("generate shock -o " + q(*dir_ / "s.h5") + " --dims 32 --steps 7")
                  .exit_code,
              0);
    const auto b =
        run_tspplay("build " + q(*dir_ / "s.h5") + " --field shock --brick 8 -o " + q(*dir_ / "s.tsp"));
    ASSERT_EQ(b.exit_code, 0) << b.err;
  }
  static void TearDownTestSuite() { delete dir_; }
  static inline fs::path* dir_ = nullptr;

  // Renders `options` into the test's folder `name` and returns it.
  static fs::path render(const std::string& name, const std::string& options) {
    const fs::path out = tsptest::temp_dir() / name;
    const auto r = run_tspplay("render " + q(*dir_ / "s.tsp") + " --size 96x72 " + options +
                               " -o " + q(out));
    EXPECT_EQ(r.exit_code, 0) << options << "\n" << r.err;
    return out;
  }
  static std::string png(int step) {
    char name[32];
    std::snprintf(name, sizeof name, "step_%04d.png", step);
    return name;
  }
  static json frame(const fs::path& out, int step) {
    const json report = tsptest::frames_json(out);
    for (const json& f : report["frames"])
      if (f["step"] == step) return f;
    ADD_FAILURE() << "no frame of step " << step << " in " << out;
    return {};
  }
};

TEST_F(RenderDeterminism, TheSameCommandTwiceIsTheSameBytesOnBothBackEnds) {
  for (const std::string backend : {"cpu", "gl"})
    for (const std::string extra : {"", " --lod 1", " --probe plane:1,0,0,-16"}) {
      const std::string options = "--steps 0:6 --backend " + backend + extra;
      const fs::path a = render("a", options), b = render("b", options);
      for (int t = 0; t <= 6; ++t)
        EXPECT_EQ(tsptest::read_file(a / png(t)), tsptest::read_file(b / png(t)))
            << options << ", step " << t;
    }
}

TEST_F(RenderDeterminism, AStepIsTheSameBytesWhateverWasDrawnBeforeIt) {
  // Refinement (on by default) at a spacing whose segments end on many brick faces.
  for (const std::string reuse : {"on", "off"}) {
    const std::string options = "--backend cpu --spacing 1.5 --shade off --reuse " + reuse;
    const fs::path all = render("all_" + reuse, options + " --steps 0:6"),
                   later = render("later_" + reuse, options + " --steps 3:6");
    // With reuse the first frame of a run is drawn whole: compare the frames after it.
    for (int t = reuse == "on" ? 4 : 3; t <= 6; ++t) {
      EXPECT_EQ(tsptest::read_file(all / png(t)), tsptest::read_file(later / png(t)))
          << options << ", step " << t;
      EXPECT_EQ(frame(all, t)["samples"], frame(later, t)["samples"]) << options << ", step " << t;
    }
  }
}

}  // namespace

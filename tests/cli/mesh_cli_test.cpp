// Unstructured input end to end: build a .pvd of .vtu meshes (six disjoint cells in a row),
// check the stencil and the physical grid in the file, and render it: the gaps between the
// cells are outside the mesh and stay background (without the stencil their padded values
// would fill them).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/json_file.h"
#include "support/paths.h"
#include "tsp/report/image.h"
#include "tsp/store/tsp_file.h"

namespace {

namespace fs = std::filesystem;
using tsptest::run_tspplay;

using tsptest::q;

// Runs of lit pixels along row y.
int lit_runs(const tsp::Image& img, int y) {
  int runs = 0;
  bool lit = false;
  for (int x = 0; x < img.width; ++x) {
    const std::uint8_t* p = img.at(x, y);
    const bool on = p[0] + p[1] + p[2] > 30;
    runs += on && !lit;
    lit = on;
  }
  return runs;
}

TEST(MeshCli, BuildStoresTheStencilAndRenderLeavesTheOutsideEmpty) {
  const fs::path dir = tsptest::temp_dir();
  const fs::path tsp = dir / "mixed.tsp";
  auto b = run_tspplay("build " + q(tsptest::test_data_dir() / "vtu" / "mixed.pvd") +
                       " --field f --resolution 45 -o " + q(tsp));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  auto f = tsp::TspFile::open(tsp.string());
  EXPECT_TRUE(f->tree().has_stencil());
  EXPECT_EQ(f->tree().octree().dims(), (tsp::Dims{45, 5, 5}));  // [0,11]x[0,1]x[0,1] by 0.25
  EXPECT_DOUBLE_EQ(f->metadata().spacing[0], 0.25);
  EXPECT_DOUBLE_EQ(f->metadata().origin[0], 0.0);
  // The .pvd's timesteps are the steps' physical times, in time order; render reports them.
  EXPECT_EQ(f->metadata().times, (std::vector<double>{0.0, 0.25, 0.5}));
  // The root's inside fraction: the gaps between the cells are outside.
  const float inside = f->tree().inside_fraction(0);
  EXPECT_GT(inside, 0.3f);
  EXPECT_LT(inside, 0.7f);

  // Every compositing, the non-TSP baseline and LOD level 1 (its stencil filtered from the
  // leaves': the 4-voxel gaps stay open at 2 level texels). Unlit: f grows along x and the view
  // looks along y, so the headlight leaves the cells at the ambient term, below the threshold.
  int k = 0;
  for (const char* c : {"--compositing rays", "--compositing boxes", "--compositing slices",
                        "--baseline", "--lod 1"}) {
    const fs::path out = dir / ("frames_" + std::to_string(k++));
    auto r = run_tspplay("render " + q(tsp) + " --tf preset:filled --view 0,0 --size 880x240 --shade off " +
                         c + " --steps 1 -o " + q(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const tsp::Image img = tsp::read_png((out / "step_0001.png").string());
    EXPECT_EQ(tsptest::frames_json(out)["frames"][0]["time"], 0.25);
    EXPECT_EQ(lit_runs(img, img.height / 2), 6) << c;
  }
}

TEST(MeshCli, UnstructuredErrorsNameTheFileAndExitNonZero) {
  const fs::path dir = tsptest::temp_dir();
  auto r = run_tspplay("build " + q(tsptest::test_data_dir() / "vtu" / "ascii_0.vtu") +
                       " --field v -o " + q(dir / "x.tsp"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("ascii_0.vtu"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("v:mag"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "x.tsp"));
  r = run_tspplay("build " + q(tsptest::test_data_dir() / "vtu" / "ascii_0.vtu") +
                  " --resolution 10 --voxel-size 1 -o " + q(dir / "x.tsp"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  // An output naming an input (here the .vtu a .vtm step points to) is refused, the input kept.
  fs::copy(tsptest::test_data_dir() / "vtu", dir / "vtu", fs::copy_options::recursive |
                                                          fs::copy_options::overwrite_existing);
  const auto before = fs::file_size(dir / "vtu" / "appended_0.vtu");
  r = run_tspplay("build " + q(dir / "vtu" / "case.vtm.series") + " -o " +
                  q(dir / "vtu" / "appended_0.vtu"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("appended_0.vtu"), std::string::npos) << r.err;
  EXPECT_EQ(fs::file_size(dir / "vtu" / "appended_0.vtu"), before);
}

}  // namespace

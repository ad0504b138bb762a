// build MESH --octree-error (issue 31 item 1, Leven's adaptive octree) from the command line:
// the OpenFOAM dam break (a remeshed series: its cell count changes) renders as its uniform
// build does; info names the adaptive tree; misuse is a clear error that leaves the output as
// it was. The octree itself is checked in tests/tsp/adaptive/adaptive_build_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/paths.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"

namespace fs = std::filesystem;
using tsptest::run_tspplay;

namespace {

using tsptest::q;

fs::path dam() {
  return tsptest::datasets_dir() / "samples/damBreakWithObstacle/damBreakWithObstacle.vtu.series";
}

TEST(AdaptiveCli, TheDamBreakRendersAsItsUniformBuild) {
  const fs::path dir = tsptest::temp_dir();
  const std::string common = q(dam()) + " --field alpha.water --resolution 64";
  auto u = run_tspplay("build " + common + " -o " + q(dir / "u.tsp"));
  ASSERT_EQ(u.exit_code, 0) << u.err;
  auto a = run_tspplay("build " + common + " --octree-error 5% -o " + q(dir / "a.tsp"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_NE(a.out.find("adaptive octree (E = 0.05)"), std::string::npos) << a.out;
  auto info = run_tspplay("info " + q(dir / "a.tsp"));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("format version 3"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("stopped above the finest level"), std::string::npos) << info.out;
  const std::string view = " --size 320x240 --tf-range 0:1";
  ASSERT_EQ(run_tspplay("render " + q(dir / "u.tsp") + " -o " + q(dir / "ru") + view).exit_code, 0);
  auto r = run_tspplay("render " + q(dir / "a.tsp") + " -o " + q(dir / "ra") + view);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* step : {"step_0000.png", "step_0001.png"}) {
    const tsp::DiffStats d = tsp::diff_images(tsp::read_png((dir / "ru" / step).string()),
                                              tsp::read_png((dir / "ra" / step).string()));
    EXPECT_LT(d.mean, 0.3) << step;
    EXPECT_LT(d.p99, 3.0) << step;
  }
}

TEST(AdaptiveCli, MisuseIsAClearErrorAndTheOutputIsKept) {
  const fs::path dir = tsptest::temp_dir();
  const fs::path out = dir / "kept.tsp";
  { std::ofstream(out) << "keep me"; }
  auto bad = run_tspplay("build " + q(dam()) + " --field alpha.water --octree-error abc -o " + q(out));
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--octree-error abc"), std::string::npos) << bad.err;
  auto neg = run_tspplay("build " + q(dam()) + " --field alpha.water --octree-error -1 -o " + q(out));
  EXPECT_NE(neg.exit_code, 0);
  auto grid = run_tspplay("build " + q(tsptest::test_data_dir() / "h5/scales.h5") +
                          " --octree-error 1 -o " + q(out));
  EXPECT_NE(grid.exit_code, 0);
  EXPECT_NE(grid.err.find("not an unstructured mesh"), std::string::npos) << grid.err;
  auto two = run_tspplay("build " + q(dam()) + " --field alpha.water,p --octree-error 1 -o " + q(out));
  EXPECT_NE(two.exit_code, 0);
  EXPECT_NE(two.err.find("builds one field"), std::string::npos) << two.err;
  EXPECT_EQ(tsptest::read_file(out), "keep me");
}

}  // namespace

// render --lod-filter distance|fov and --eye (issue 31 item 4): the cut the filter chose is the
// one frames.json reports, finest around a placed eye; the filters and the eye are usage errors
// when misused. The cuts themselves are checked against their definition in
// tests/tsp/lod/selection_filter_test.cpp, the eye's picture in tests/render.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/json_file.h"
#include "support/paths.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"
#include "tsp/store/tsp_file.h"

namespace fs = std::filesystem;
using tsptest::run_tspplay;

namespace {

using tsptest::q;

TEST(LodFilterCli, DistanceAroundAPlacedEyeAndFovCutsAreReported) {
  const fs::path dir = tsptest::temp_dir();
  ASSERT_EQ(run_tspplay("generate shock -o " + q(dir / "s.h5") + " --dims 48 --steps 2").exit_code, 0);
  ASSERT_EQ(run_tspplay("build " + q(dir / "s.h5") + " --field shock --brick 8 -o " + q(dir / "s.tsp"))
                .exit_code,
            0);
  const int leaves = tsp::TspFile::open((dir / "s.tsp").string())->tree().octree().brick_count();
  const std::string common = "render " + q(dir / "s.tsp") + " --steps 1 --size 96x72 ";
  const std::string eye = "--eye 24,6,20 --view 20,5 ";
  auto r = run_tspplay(common + eye + "--lod-filter distance -o " + q(dir / "dist"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_tspplay(common + eye + "-o " + q(dir / "full"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json d = tsptest::frames_json(dir / "dist");
  EXPECT_EQ(d["lod"], "filter");
  EXPECT_EQ(d["lod_filter"], "distance");
  EXPECT_EQ(d["projection"], "perspective");
  EXPECT_EQ(d["eye"], (std::vector<double>{24, 6, 20}));
  const nlohmann::json cut = d["frames"][0]["lod"];
  const std::vector<int> per_level = cut["nodes_per_level"];
  ASSERT_GE(per_level.size(), 2u);
  EXPECT_GT(per_level[0], 0);  // full resolution around the eye
  int coarse = 0;
  for (std::size_t k = 1; k < per_level.size(); ++k) coarse += per_level[k];
  EXPECT_GT(coarse, 0);  // coarser away from it
  EXPECT_LT(int(cut["cut_size"]), leaves);  // fewer nodes than the leaf bricks
  // The picture from inside the volume is not empty and close to the full-resolution one.
  const tsp::Image full = tsp::read_png((dir / "full" / "step_0001.png").string());
  const tsp::Image dist = tsp::read_png((dir / "dist" / "step_0001.png").string());
  EXPECT_LT(tsp::diff_images(dist, full).mean, 5.0);

  // fov: with the orbit camera and K = 1 a coarse cut (tiles under half the field of view).
  r = run_tspplay(common + "--perspective --lod-filter fov -o " + q(dir / "fov"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json f = tsptest::frames_json(dir / "fov");
  EXPECT_EQ(f["lod_filter"], "fov");
  EXPECT_LT(int(f["frames"][0]["lod"]["cut_size"]), leaves);

  // Misuse: a filter with another cut choice, unknown filters, a bad eye.
  for (const std::string bad : {"--lod-filter distance --lod 2", "--lod-filter fov --target-fps 10",
                                "--lod-filter near", "--lod-filter fov:0", "--eye 1,2"}) {
    r = run_tspplay(common + bad + " -o " + q(dir / "bad"));
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_NE(r.err.find(bad.substr(0, bad.find(' '))), std::string::npos) << bad << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir / "bad" / "frames.json")) << bad;
  }
}

}  // namespace

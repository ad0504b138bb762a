// render --surface boundary (issue 31 item 2, TetSplat's Shell): the mesh's boundary drawn as
// opaque lit splats coloured by a field of its own, against the analytic Lambert term of the
// faces that look at the camera; a probe opens it; a larger minimum splat size draws fewer
// splats; misuse is a usage error. The boundary and the hierarchy themselves are checked in
// tests/tsp/surface/splat_tree_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "support/json_file.h"
#include "support/paths.h"
#include "tsp/core/color.h"
#include "tsp/report/image.h"

namespace fs = std::filesystem;
using tsptest::run_tspplay;

namespace {

using tsptest::q;

// Pixels of img within ΔE 2 of the 8-bit colour (r, g, b).
int pixels_near(const tsp::Image& img, double r, double g, double b) {
  const tsp::Luv want = tsp::srgb_to_luv(r, g, b);
  int n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.at(x, y);
      if (tsp::delta_e_luv(tsp::srgb8_to_luv(p[0], p[1], p[2]), want) < 2) ++n;
    }
  return n;
}

// The fixture: six disjoint unit cells along x (tetra, voxel, hexahedron, wedge, pyramid,
// polyhedron at x = 0, 2, …, 10), cell field c = 7·cell + t (tests/data/make_mesh_fixtures.py).
struct SurfaceCli : ::testing::Test {
  fs::path dir = tsptest::temp_dir();
  std::string mesh = (tsptest::test_data_dir() / "vtu" / "binary_%d.vtu").string();
  void SetUp() override {
    auto r = run_tspplay("build " + q(mesh) + " --field f --resolution 96 -o " + q(dir / "m.tsp"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // A grey ramp over c: grey c/35.
    std::ofstream(dir / "ramp.json") << R"({"range": [0, 35], "points": [[0, 0, 0, 0, 1], [35, 1, 1, 1, 1]]})";
  }
  std::string render(const std::string& out, const std::string& extra) {
    return "render " + q(dir / "m.tsp") + " --steps 0 --size 960x240 --view 0,0 --surface boundary "
           "--surface-mesh " + q(mesh) + " --surface-field c --surface-tf " + q(dir / "ramp.json") +
           " " + extra + " -o " + q(dir / out);
  }
};

TEST_F(SurfaceCli, FacesTowardsTheCameraShowTheirCellsColourLitByLambert) {
  auto r = run_tspplay(render("lit", ""));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tsp::Image img = tsp::read_png((dir / "lit" / "step_0000.png").string());
  // View 0,0 looks along +y: the faces at y = 0 face the headlight (n·l = 1), so a face of cell
  // k shows grey g = (7k)/35 lit as g·(ambient + diffuse) + specular = 0.8·g + 0.2.
  for (int k : {0, 1, 2, 3, 5}) {  // the pyramid's faces are all slanted
    const double g = 0.8 * (7.0 * k / 35.0) + 0.2;
    EXPECT_GT(pixels_near(img, g, g, g), 200) << "cell " << k << ": grey " << g;
  }
  const nlohmann::json j = tsptest::frames_json(dir / "lit");
  EXPECT_EQ(j["surface"], "boundary");
  EXPECT_EQ(j["surface_field"], "c");
  EXPECT_GT(int(j["frames"][0]["surface_splats"]), 0);

  // Unlit: the TF's grey itself.
  r = run_tspplay(render("unlit", "--shade off"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tsp::Image flat = tsp::read_png((dir / "unlit" / "step_0000.png").string());
  EXPECT_GT(pixels_near(flat, 14.0 / 35, 14.0 / 35, 14.0 / 35), 200);
}

TEST_F(SurfaceCli, AProbeCutsTheSurfaceAndLargerSplatsAreFewer) {
  ASSERT_EQ(run_tspplay(render("whole", "")).exit_code, 0);
  // Keep x ≤ 3.5: the tetrahedron and the voxel stay, the hexahedron (x in [4, 5]) and the
  // cells beyond it go, surface and volume.
  auto r = run_tspplay(render("cut", "--probe plane:1,0,0,3.5"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tsp::Image whole = tsp::read_png((dir / "whole" / "step_0000.png").string());
  const tsp::Image cut = tsp::read_png((dir / "cut" / "step_0000.png").string());
  const double voxel = 0.8 * 0.2 + 0.2, hexahedron = 0.8 * 0.4 + 0.2;
  EXPECT_GT(pixels_near(whole, hexahedron, hexahedron, hexahedron), 200);
  EXPECT_EQ(pixels_near(cut, hexahedron, hexahedron, hexahedron), 0);
  EXPECT_GT(pixels_near(cut, voxel, voxel, voxel), 200);
  EXPECT_LT(int(tsptest::frames_json(dir / "cut")["frames"][0]["surface_splats"]),
            int(tsptest::frames_json(dir / "whole")["frames"][0]["surface_splats"]));
  // Coarser cuts: no more splats, and one splat for the whole surface once it is that small.
  int previous = int(tsptest::frames_json(dir / "whole")["frames"][0]["surface_splats"]);
  for (int px : {60, 200, 4096}) {
    const std::string out = "px" + std::to_string(px);
    ASSERT_EQ(run_tspplay(render(out, "--surface-px " + std::to_string(px))).exit_code, 0);
    const int n = tsptest::frames_json(dir / out)["frames"][0]["surface_splats"];
    EXPECT_LE(n, previous) << px;
    if (px == 4096) {
      EXPECT_EQ(n, 1);
    }
    previous = n;
  }
  EXPECT_LT(previous, int(tsptest::frames_json(dir / "whole")["frames"][0]["surface_splats"]));
}

// --surface-target-ms: the minimum splat size follows the surface pass's time, at most a factor
// 2 a frame, within [0.5, 4096] — up while slower than the target, down while faster (targets
// no frame can miss or meet, so the direction does not depend on the machine).
TEST_F(SurfaceCli, ATargetTimeMovesTheMinimumSplatSize) {
  for (const auto& [target, want] : {std::pair<std::string, std::vector<double>>{"0.0001", {1, 2, 4, 8}},
                                     {"60000", {1, 0.5, 0.5, 0.5}}}) {
    const std::string out = "target" + target;
    auto r = run_tspplay(render(out, "--passes 4 --surface-target-ms " + target));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = tsptest::frames_json(dir / out);
    EXPECT_EQ(double(j["surface_target_ms"]), std::stod(target));
    ASSERT_EQ(j["frames"].size(), want.size());
    for (std::size_t i = 0; i < want.size(); ++i)
      EXPECT_EQ(double(j["frames"][i]["surface_px"]), want[i]) << target << " frame " << i;
  }
}

TEST_F(SurfaceCli, MisuseIsAUsageError) {
  const std::string base = "render " + q(dir / "m.tsp") + " --steps 0 --size 64x48 -o " + q(dir / "x") + " ";
  for (const std::string& bad :
       {std::string("--surface boundary"),                                     // no mesh
        "--surface-mesh " + q(mesh),                                           // no --surface
        "--surface boundary --surface-mesh " + q(mesh) + " --compositing slices",
        "--surface boundary --surface-mesh " + q(mesh) + " --surface-px -1",
        "--surface boundary --surface-mesh " + q(mesh) + " --surface-field nosuch",
        std::string("--surface-target-ms 10"),                                  // no --surface
        "--surface boundary --surface-mesh " + q(mesh) + " --surface-target-ms -1"}) {
    const auto r = run_tspplay(base + bad);
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_NE(r.err.find("error"), std::string::npos) << bad << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir / "x")) << bad;
  }
}

TEST_F(SurfaceCli, AMeshThatIsNotTheFilesIsRefusedNamingBoth) {
  // Another mesh: one step of the three, then a tetrahedron elsewhere over three steps.
  for (int t = 0; t < 3; ++t)
    std::ofstream(dir / ("far_" + std::to_string(t) + ".vtu")) << R"(<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
<UnstructuredGrid><Piece NumberOfPoints="4" NumberOfCells="1">
<PointData><DataArray type="Float32" Name="f" format="ascii">0 1 2 3</DataArray></PointData>
<CellData><DataArray type="Float32" Name="c" format="ascii">5</DataArray></CellData>
<Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">100 100 100 101 100 100 100 101 100 100 100 101</DataArray></Points>
<Cells><DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 3</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">4</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">10</DataArray></Cells>
</Piece></UnstructuredGrid></VTKFile>
)";
  const std::string one_step = (tsptest::test_data_dir() / "vtu" / "binary_0.vtu").string();
  const std::string far = (dir / "far_%d.vtu").string();
  for (const auto& [other, why] : {std::pair{one_step, std::string("steps")},
                                   std::pair{far, std::string("along x the mesh spans")}}) {
    const auto r = run_tspplay("render " + q(dir / "m.tsp") + " --steps 0 --size 64x48 "
                               "--surface boundary --surface-field c --surface-mesh " + q(other) +
                               " -o " + q(dir / "x"));
    EXPECT_EQ(r.exit_code, 2) << other << ": " << r.err;
    EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(other), std::string::npos) << r.err;
    EXPECT_NE(r.err.find((dir / "m.tsp").string()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "x"));
  }
}

}  // namespace

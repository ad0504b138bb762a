// The curvilinear readers (.vts and its series, PLOT3D .xyz + .q) against the fixtures'
// formulas (tests/data/make_structured_fixtures.py; VTK's own PLOT3D reader read the same files
// back there), their voxelization against the analytic field (trilinear isoparametric sampling
// reproduces a field linear in x, y, z exactly), and their errors on bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "support/paths.h"
#include "tsp/core/error.h"
#include "tsp/source/open_mesh_source.h"
#include "tsp/voxelize/open_input.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;

constexpr int kNi = 6, kNj = 5, kNk = 4;
constexpr int kPoints = kNi * kNj * kNk;
constexpr int kCells = (kNi - 1) * (kNj - 1) * (kNk - 1);

fs::path dir() { return tsptest::test_data_dir() / "structured"; }

// The fixture's warped grid point (i, j, k).
std::array<double, 3> grid_point(int i, int j, int k) {
  return {0.5 * i + 0.1 * std::sin(0.7 * j), 0.4 * j + 0.08 * k, 0.6 * k + 0.05 * i * j};
}

double f_of(const double* x, int t) { return 1 + 2 * x[0] + 3 * x[1] - x[2] + 10 * t; }
double rho_of(const double* x, double t) { return 1 + 0.1 * x[0] + 0.2 * x[1] + 0.3 * x[2] + t; }

TEST(StructuredGrid, VtsSeriesReadsTheWarpedGridAsHexahedra) {
  auto s = open_mesh_source((dir() / "warped.vts.series").string(), "f");
  ASSERT_EQ(s->steps(), 2);
  EXPECT_EQ(s->times(), (std::vector<double>{0.5, 1.5}));
  const Mesh m = s->read_step(1);
  ASSERT_EQ(m.point_count(), kPoints);
  ASSERT_EQ(m.cell_count(), kCells);
  for (int k = 0, p = 0; k < kNk; ++k)
    for (int j = 0; j < kNj; ++j)
      for (int i = 0; i < kNi; ++i, ++p) {
        const std::array<double, 3> x = grid_point(i, j, k);
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(m.points[std::size_t(3 * p + a)], x[std::size_t(a)], 1e-6);  // read as float
        EXPECT_FLOAT_EQ(m.values[std::size_t(p)], float(f_of(x.data(), 1)));
      }
  for (CellType t : m.types) EXPECT_EQ(t, CellType::hexahedron);
  // VTK's hexahedron order: the k face counter-clockwise, then the k + 1 face.
  const std::vector<std::int64_t> first(m.connectivity.begin(), m.connectivity.begin() + 8);
  EXPECT_EQ(first, (std::vector<std::int64_t>{0, 1, 7, 6, 30, 31, 37, 36}));
  const Mesh c = open_mesh_source((dir() / "warped_1.vts").string(), "c")->read_step(0);
  ASSERT_TRUE(c.cell_values);
  for (int k = 0; k < kCells; ++k) EXPECT_EQ(c.values[std::size_t(k)], float(k + 100));
  const Mesh vx = open_mesh_source((dir() / "warped_0.vts").string(), "v:z")->read_step(0);
  for (int p = 0; p < kPoints; ++p)
    EXPECT_FLOAT_EQ(vx.values[std::size_t(p)], float(m.points[std::size_t(3 * p + 2)]));
}

TEST(StructuredGrid, Plot3dReadsTheGridAndEverySolutionField) {
  // flow_%d.q's grid is the only .xyz beside it.
  auto s = open_mesh_source((dir() / "plot3d" / "flow_%d.q").string(), "Density");
  ASSERT_EQ(s->steps(), 2);
  EXPECT_EQ(s->times(), (std::vector<double>{0.5, 1.5}));
  const Mesh m = s->read_step(1);
  ASSERT_EQ(m.point_count(), kPoints);
  ASSERT_EQ(m.cell_count(), kCells);
  const auto field = [](const char* name) {
    return open_mesh_source((dir() / "plot3d" / "flow_1.q").string(), name)->read_step(0).values;
  };
  const std::vector<float> p = field("Pressure"), u = field("Velocity:y"), e = field("StagnationEnergy"),
                           mx = field("Momentum:x");
  for (int k = 0, q = 0; k < kNk; ++k)
    for (int j = 0; j < kNj; ++j)
      for (int i = 0; i < kNi; ++i, ++q) {
        const std::array<double, 3> x = grid_point(i, j, k);
        const double rho = rho_of(x.data(), 1.5);
        const double energy = 2.5 + x[0];
        const double m2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
        EXPECT_FLOAT_EQ(m.values[std::size_t(q)], float(rho));
        EXPECT_FLOAT_EQ(e[std::size_t(q)], float(energy));
        EXPECT_FLOAT_EQ(mx[std::size_t(q)], float(x[0]));
        EXPECT_NEAR(u[std::size_t(q)], x[1] / rho, 1e-6);
        EXPECT_NEAR(p[std::size_t(q)], 0.4 * (energy - 0.5 * m2 / rho), 1e-6);
      }
}

TEST(StructuredGrid, Plot3dMultiBlockSinglePrecisionBigEndianWithIblank) {
  const fs::path d = dir() / "plot3d_multi";
  auto s = open_mesh_source((d / "multi.q").string(), "", false, (d / "multi.xyz").string());
  ASSERT_EQ(s->steps(), 1);
  EXPECT_TRUE(s->times().empty());  // one step: no series of times
  const Mesh m = s->read_step(0);
  ASSERT_EQ(m.point_count(), 2 * kPoints);
  // Block 1's points with i = 0 are blanked: its cells touching them are dropped.
  EXPECT_EQ(m.cell_count(), kCells + (kNi - 2) * (kNj - 1) * (kNk - 1));
  for (int q = 0; q < 2 * kPoints; ++q) {
    const double* x = m.points.data() + 3 * q;
    EXPECT_NEAR(m.values[std::size_t(q)], rho_of(x, 0.0), 1e-6);
  }
  EXPECT_NEAR(m.bounds().lo[0], 0.0, 1e-6);
  EXPECT_NEAR(m.bounds().hi[0], 4 + 2.5 + 0.1 * std::sin(0.7 * 2), 1e-6);  // i = 5, j = 2
}

TEST(StructuredGrid, VoxelizedValuesEqualTheLinearFieldAtVoxelCentres) {
  VoxelizeOptions vo;
  vo.resolution = 24;
  for (const auto& [input, field, grid] :
       std::vector<std::array<std::string, 3>>{{(dir() / "warped_1.vts").string(), "f", ""},
                                               {(dir() / "plot3d" / "flow_1.q").string(), "Density", ""}}) {
    SCOPED_TRACE(input);
    SourceOptions so;
    so.field = field;
    so.plot3d_grid = grid;
    auto v = open_input(input, so, vo);
    const Dims d = v->dims();
    std::vector<float> values(std::size_t(d.count()));
    std::vector<std::uint8_t> inside(values.size());
    v->read_step_inside(0, values, inside);
    const auto o = v->origin(), h = v->spacing();
    std::int64_t in = 0;
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x) {
          const std::size_t i = std::size_t(x + std::int64_t(d.x) * (y + std::int64_t(d.y) * z));
          if (!inside[i]) continue;
          ++in;
          const double p[3] = {o[0] + x * h[0], o[1] + y * h[1], o[2] + z * h[2]};
          const double want = field == "f" ? f_of(p, 1) : rho_of(p, 1.5);
          ASSERT_NEAR(values[i], want, 2e-5 * std::max(1.0, std::abs(want))) << x << "," << y << "," << z;
        }
    EXPECT_GT(in, d.count() / 4);  // the warped block fills a good part of its box
  }
}

TEST(StructuredGrid, BadInputsAreClearErrors) {
  const fs::path tmp = tsptest::temp_dir();
  const std::string multi_q = (dir() / "plot3d_multi" / "multi.q").string();
  try {  // two grids beside the solution: ambiguous
    open_mesh_source(multi_q, "");
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("2 .xyz files"), std::string::npos) << e.what();
  }
  EXPECT_THROW(open_mesh_source((dir() / "plot3d" / "grid.xyz").string(), ""), UsageError);
  try {
    open_mesh_source((dir() / "plot3d" / "flow_0.q").string(), "Temperature");
    FAIL() << "no error";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("StagnationEnergy"), std::string::npos) << e.what();
  }
  try {  // the solution's blocks against another grid's
    open_mesh_source((dir() / "plot3d" / "flow_0.q").string(), "", false,
                     (dir() / "plot3d_multi" / "multi.xyz").string());
    FAIL() << "no error";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("6x5x4"), std::string::npos) << e.what();
  }
  // A truncated solution fits no layout; the message names the file and its size.
  const std::string q = tsptest::read_file(dir() / "plot3d" / "flow_0.q");
  fs::copy_file(dir() / "plot3d" / "grid.xyz", tmp / "grid.xyz");
  std::ofstream(tmp / "cut.q", std::ios::binary) << q.substr(0, q.size() - 8);
  try {
    open_mesh_source((tmp / "cut.q").string(), "");
    FAIL() << "no error";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("cut.q: " + std::to_string(q.size() - 8) + " bytes"),
              std::string::npos) << e.what();
  }
  // A header declaring 2^31 - 1 points per axis fits no layout either (nothing allocated).
  std::string huge = q;
  for (int a = 0; a < 3; ++a) huge.replace(std::size_t(4 + 4 * a), 4, "\xff\xff\xff\x7f", 4);
  std::ofstream(tmp / "huge.q", std::ios::binary) << huge;
  EXPECT_THROW(open_mesh_source((tmp / "huge.q").string(), ""), FormatError);
  // A .vts whose extent is a surface has no volume.
  std::string vts = tsptest::read_file(dir() / "warped_0.vts");
  for (std::size_t at; (at = vts.find("0 5 0 4 0 3")) != std::string::npos;)
    vts.replace(at, 11, "0 5 0 4 0 0");
  std::ofstream(tmp / "flat.vts", std::ios::binary) << vts;
  try {
    open_mesh_source((tmp / "flat.vts").string(), "f")->read_step(0);
    FAIL() << "no error";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("a surface or a line"), std::string::npos) << e.what();
  }
}

TEST(StructuredGrid, BuildAndInfoFromTheCommandLine) {
  const fs::path tmp = tsptest::temp_dir();
  const tsptest::RunResult b = tsptest::run_tspplay(
      "build " + tsptest::quote(dir() / "plot3d_multi" / "multi.q") + " --xyz " +
      tsptest::quote(dir() / "plot3d_multi" / "multi.xyz") + " --field Pressure --resolution 20 -o " +
      tsptest::quote(tmp / "m.tsp"));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const tsptest::RunResult v = tsptest::run_tspplay(
      "build " + tsptest::quote(dir() / "warped.vts.series") + " --field f -o " +
      tsptest::quote(tmp / "w.tsp"));
  ASSERT_EQ(v.exit_code, 0) << v.err;
  const tsptest::RunResult i = tsptest::run_tspplay("info " + tsptest::quote(tmp / "w.tsp"));
  EXPECT_NE(i.out.find("warped.vts.series, PointData f (2 steps)"), std::string::npos) << i.out;
  EXPECT_NE(i.out.find("0.5 .. 1.5"), std::string::npos) << i.out;
}

}  // namespace
}  // namespace tsp

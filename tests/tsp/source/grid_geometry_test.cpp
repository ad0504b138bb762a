// Origin and Spacing of image data reach the source (and so the .tsp): .vti and VTKHDF, point
// and cell fields, and bad values are named.
#include "tsp/source/grid_geometry.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/paths.h"
#include "tsp/core/error.h"
#include "tsp/source/open_source.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;

fs::path vti_with(const std::string& origin, const std::string& spacing) {
  std::ifstream in(tsptest::test_data_dir() / "vti" / "ascii_0.vti");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string t = ss.str();
  t.replace(t.find("Origin=\"0 0 0\""), 14, "Origin=\"" + origin + "\"");
  t.replace(t.find("Spacing=\"1 1 1\""), 15, "Spacing=\"" + spacing + "\"");
  const fs::path p = tsptest::temp_dir() / "geometry.vti";
  std::ofstream(p) << t;
  return p;
}

TEST(GridGeometry, VtiOriginAndSpacingReachTheSource) {
  const fs::path p = vti_with("1 2 3", "0.5 0.25 2");
  SourceOptions o;
  o.field = "f";
  auto s = open_source(p.string(), o);
  EXPECT_EQ(s->origin(), (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(s->spacing(), (std::array<double, 3>{0.5, 0.25, 2}));
  o.field = "c";  // cell data: the cell centres
  s = open_source(p.string(), o);
  EXPECT_EQ(s->origin(), (std::array<double, 3>{1.25, 2.125, 4}));
  EXPECT_THROW(open_source(vti_with("0 0 0", "0 1 1").string(), o), FormatError);
  EXPECT_THROW(open_source(vti_with("0 nan 0", "1 1 1").string(), o), FormatError);
}

TEST(GridGeometry, Hdf5DimensionScalesThatStepUniformly) {
  SourceOptions o;
  o.field = "f";
  auto s = open_source((tsptest::test_data_dir() / "h5" / "scales.h5").string(), o);
  EXPECT_EQ(s->dims(), (Dims{5, 4, 3}));
  EXPECT_EQ(s->origin(), (std::array<double, 3>{0, 0, 10}));    // x's scale is not uniform
  EXPECT_EQ(s->spacing(), (std::array<double, 3>{1, 0.5, 2}));
  o.field = "";
  auto plain = open_source((tsptest::test_data_dir() / "h5" / "grid4d.h5").string(), o);
  EXPECT_EQ(plain->spacing(), (std::array<double, 3>{1, 1, 1}));  // no scales: 0 and 1
  // The time dimension's coordinate variable gives the steps' times.
  EXPECT_EQ(s->times(), (std::vector<double>{0, 1, 2}));
  EXPECT_TRUE(plain->times().empty());
}

// A small file shaped like WRF output (tests/data/make_fixtures.py, make_wrf_like): DX, DY,
// geopotential levels 300 m apart from 100 m, Times 3 hours apart. As stored (--vertical-levels
// native) the mass levels lie at the mean heights, 250, 550 and 850 m.
TEST(GridGeometry, WrfLikeFileGivesSpacingOriginAndTimes) {
  SourceOptions o;
  o.field = "T";
  o.vertical.mode = VerticalLevels::Mode::native;
  auto s = open_source((tsptest::test_data_dir() / "h5" / "wrf_like.nc").string(), o);
  EXPECT_EQ(s->dims(), (Dims{5, 4, 3}));
  EXPECT_DOUBLE_EQ(s->spacing()[0], 2000);
  EXPECT_DOUBLE_EQ(s->spacing()[1], 3000);
  EXPECT_NEAR(s->spacing()[2], 300, 1e-9);
  EXPECT_NEAR(s->origin()[2], 250, 1e-9);
  EXPECT_EQ(s->times(), (std::vector<double>{0, 10800}));
  // At their heights (the default): PH's wobble of up to ±2 m²/s² moves each column by up to
  // ±2/9.81 m, so the grid spans 250 − 2/9.81 to 850 + 2/9.81 m in 3 planes (the 300 m layers).
  o.vertical = {};
  auto r = open_source((tsptest::test_data_dir() / "h5" / "wrf_like.nc").string(), o);
  EXPECT_EQ(r->dims(), (Dims{5, 4, 3}));
  EXPECT_NEAR(r->origin()[2], 250 - 2 / 9.81, 1e-9);
  EXPECT_NEAR(r->spacing()[2], (600 + 4 / 9.81) / 2, 1e-9);
  EXPECT_TRUE(r->has_stencil());
  EXPECT_EQ(r->times(), (std::vector<double>{0, 10800}));
}

// WRF's Times (one "YYYY-MM-DD_HH:MM:SS" per step, 3-hourly from 2005-08-28_12:00:00) as seconds
// since the first step.
TEST(GridGeometry, WrfTimesAreSecondsSinceTheFirstStep) {
  const auto wrf = tsptest::katrina_file();
  if (!std::filesystem::exists(wrf)) GTEST_SKIP() << "shared data absent: " << wrf;
  SourceOptions o;
  o.field = "T";
  EXPECT_EQ(open_source(wrf.string(), o)->times(),
            (std::vector<double>{0, 3 * 3600, 6 * 3600, 9 * 3600}));
}

TEST(GridGeometry, SeriesListsNameTheStepsTimes) {
  SourceOptions o;
  o.field = "f";
  // The fixtures list steps 2, 0, 1 at times 0.5, 0.0, 0.25: sorted by time.
  auto pvd = open_source((tsptest::test_data_dir() / "vti" / "ascii.pvd").string(), o);
  EXPECT_EQ(pvd->times(), (std::vector<double>{0.0, 0.25, 0.5}));
  auto series = open_source((tsptest::test_data_dir() / "vti" / "ascii.vti.series").string(), o);
  EXPECT_EQ(series->times(), (std::vector<double>{0.0, 0.25, 0.5}));
  auto one = open_source((tsptest::test_data_dir() / "vti" / "ascii_0.vti").string(), o);
  EXPECT_TRUE(one->times().empty());  // a single file names no time
}

TEST(GridGeometry, VtkhdfImageAndTheRule) {
  SourceOptions o;
  auto s = open_source((tsptest::test_data_dir() / "h5" / "vtkhdf_static.hdf").string(), o);
  EXPECT_EQ(s->spacing(), (std::array<double, 3>{1, 1, 1}));
  const io::GridGeometry g =
      io::image_geometry(std::vector<double>{1, 2, 3}, std::vector<double>{2, 2, 2}, true, "x");
  EXPECT_EQ(g.origin, (std::array<double, 3>{2, 3, 4}));
  EXPECT_THROW(io::image_geometry(std::vector<double>{1, 2}, std::nullopt, false, "x"), FormatError);
  EXPECT_THROW(io::image_geometry(std::nullopt, std::vector<double>{1, -1, 1}, false, "x"),
               FormatError);
}

}  // namespace
}  // namespace tsp

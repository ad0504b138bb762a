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

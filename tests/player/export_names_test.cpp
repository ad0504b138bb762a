// The dataset part of the window's saved names (player/export_names.h): S's pictures and movies
// drop every known input extension (issue 47 walk 5: the dam break's S saved
// damBreakWithObstacle.vtu_alpha.water_step_0000.png).
#include "player/export_names.h"

#include <gtest/gtest.h>

namespace {

using tspplayer::dataset_name;

TEST(PlayerExportNames, StripsEveryKnownInputExtension) {
  EXPECT_EQ(dataset_name("datasets/samples/damBreakWithObstacle/damBreakWithObstacle.vtu.series"),
            "damBreakWithObstacle");
  EXPECT_EQ(dataset_name("/tmp/walk5/data/hotPlume_32.h5"), "hotPlume_32");
  EXPECT_EQ(dataset_name("ci_test_file.nc"), "ci_test_file");
  EXPECT_EQ(dataset_name("shock_64x64x64_32.tsp"), "shock_64x64x64_32");
  EXPECT_EQ(dataset_name("can.VTM"), "can");
  EXPECT_EQ(dataset_name("grid.vts"), "grid");
  EXPECT_EQ(dataset_name("img.vti.series"), "img");
  EXPECT_EQ(dataset_name("run.pvd"), "run");
  EXPECT_EQ(dataset_name("a.vtkhdf"), "a");
  EXPECT_EQ(dataset_name("u_%04d.raw"), "u_%04d");
  // Other dots are the name's own.
  EXPECT_EQ(dataset_name("run.2024.h5"), "run.2024");
  EXPECT_EQ(dataset_name("notes.txt"), "notes.txt");
  // Nothing left: a name of its own.
  EXPECT_EQ(dataset_name(".h5"), ".h5");
  EXPECT_EQ(dataset_name(""), "tspplay");
}

}  // namespace

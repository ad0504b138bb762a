// The dataset part of the window's saved names (player/export_names.h): S's pictures and movies
// drop every known input extension (issue 47 walk 5: the dam break's S saved
// damBreakWithObstacle.vtu_alpha.water_step_0000.png).
#include "player/export_names.h"

#include <gtest/gtest.h>

#include <utility>

namespace {

using tspplayer::dataset_name;

TEST(PlayerExportNames, StripsEveryKnownInputExtension) {
  const std::pair<const char*, const char*> named[] = {
      {"datasets/samples/damBreakWithObstacle/damBreakWithObstacle.vtu.series",
       "damBreakWithObstacle"},
      {"/tmp/walk5/data/hotPlume_32.h5", "hotPlume_32"},
      {"ci_test_file.nc", "ci_test_file"},
      {"shock_64x64x64_32.tsp", "shock_64x64x64_32"},
      {"can.VTM", "can"},
      {"grid.vts", "grid"},
      {"img.vti.series", "img"},
      {"run.pvd", "run"},
      {"a.vtkhdf", "a"},
      {"u_%04d.raw", "u_%04d"},
      // Other dots are the name's own.
      {"run.2024.h5", "run.2024"},
      {"notes.txt", "notes.txt"},
      // Nothing left: a name of its own.
      {".h5", ".h5"},
      {"", "tspplay"}};
  for (const auto& [input, name] : named) EXPECT_EQ(dataset_name(input), name) << input;
}

}  // namespace

// File > Open's filter: the names of the kinds of file play reads, against a hand-made list.
#include "jobs/play_input.h"

#include <gtest/gtest.h>

namespace tspgl {
namespace {

TEST(PlayInput, KnownInputNamesAreTheKindsPlayReads) {
  for (const char* name : {"run.tsp", "a/b/T.h5", "x.hdf5", "can_0.hdf", "s.he5", "wrf.nc", "w.nc4",
                           "m.vtkhdf", "step.vti", "mesh.vtu", "case.vtm", "case.pvd",
                           "img.vti.series", "mesh.vtu.series", "case.vtm.series", "u_0001.raw",
                           "grid.vts", "grid.vts.series", "flow_0001.q",
                           "UPPER.H5", "Mixed.Vtu"})
    EXPECT_TRUE(has_input_extension(name)) << name;
  for (const char* name : {"", "notes.txt", "frame.png", "log", "run.tsp.log", "h5", ".h5",
                           "movie.mp4", "tf.json", "archive.tar.gz", "x.series", "data.vt"})
    EXPECT_FALSE(has_input_extension(name)) << name;
}

}  // namespace
}  // namespace tspgl

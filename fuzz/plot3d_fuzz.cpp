// Fuzz target: a PLOT3D grid (.xyz) and solution (.q). The input's first two bytes (little
// endian) say where the grid's bytes end and the solution's begin; the layout detection, block
// sizes against the file sizes, IBLANK and every derived field are read, and every step
// voxelized every way (mesh_fuzz.h).
#include <algorithm>

#include "mesh_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const std::size_t split = std::min<std::size_t>(size - 2, std::size_t(data[0]) | (std::size_t(data[1]) << 8));
  const std::string grid = tspfuzz::write_input("grid.xyz", data + 2, split);
  const std::string q = tspfuzz::write_input("flow.q", data + 2 + split, size - 2 - split);
  tspfuzz::expect_clean([&] {
    for (const char* field : {"Density", "Pressure", "Velocity:mag"}) {
      auto s = tsp::open_mesh_source(q, field, false, grid);
      for (int t = 0; t < s->steps(); ++t) (void)s->read_step(t);
    }
  });
  tspfuzz::voxelize_every_way(q, grid);
  return 0;
}

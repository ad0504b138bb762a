// Fuzz target: one .vts file (VTK XML structured grid: Extent, points, point and cell data in
// every encoding VtkDocument decodes) read through open_mesh_source, every step voxelized every
// way (mesh_fuzz.h).
#include "mesh_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tspfuzz::voxelize_every_way(tspfuzz::write_input("input.vts", data, size));
  return 0;
}

// Fuzz target: one .vtu file (VTK XML unstructured grid: ascii, base64, appended raw/base64,
// zlib, UInt32/UInt64 headers, polyhedron face streams) read through open_mesh_source, every
// step voxelized every way (mesh_fuzz.h).
#include "mesh_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tspfuzz::voxelize_every_way(tspfuzz::write_input("input.vtu", data, size));
  return 0;
}

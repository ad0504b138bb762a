// Fuzz target: one VTKHDF UnstructuredGrid file (partitions, Steps offsets, point and cell data)
// read through open_mesh_source, every step voxelized every way (mesh_fuzz.h).
#include "mesh_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tspfuzz::voxelize_every_way(tspfuzz::write_input("input.hdf", data, size));
  return 0;
}

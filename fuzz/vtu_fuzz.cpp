// Fuzz target: one .vtu file (VTK XML unstructured grid: ascii, base64, appended raw/base64,
// zlib, UInt32/UInt64 headers, polyhedron face streams) read through open_mesh_source, every
// step voxelized on a small grid (both hexahedron modes).
#include <vector>

#include "fuzz_input.h"
#include "tsp/source/open_mesh_source.h"
#include "tsp/voxelize/voxelized_source.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = tspfuzz::write_input("input.vtu", data, size);
  tspfuzz::expect_clean([&] {
    auto s = tsp::open_mesh_source(path, "");
    for (int t = 0; t < s->steps(); ++t) {
      const tsp::Mesh m = s->read_step(t);
      tsp::VoxelizeOptions o;
      o.resolution = 12;
      const tsp::VoxelGrid g = tsp::choose_grid(m.bounds(), 0, o);
      std::vector<float> v(std::size_t(g.dims.count()));
      std::vector<std::uint8_t> in(v.size());
      tsp::SampleOptions so;
      so.threads = 1;
      tsp::voxelize(m, g, v, in, so);
      so.hex = tsp::HexSampling::tetrahedra;
      tsp::voxelize(m, g, v, in, so);
      so.kind = tsp::VoxelizerKind::scan;
      so.antialias = 2;
      tsp::voxelize(m, g, v, in, so);
    }
  });
  return 0;
}

// What the unstructured-grid fuzz targets share: open a mesh input and voxelize every step on a
// small grid with each voxelizer (A in both hexahedron modes, B with 2× anti-aliasing).
#pragma once
#include <string>
#include <vector>

#include "fuzz_input.h"
#include "tsp/source/open_mesh_source.h"
#include "tsp/voxelize/voxelized_source.h"

namespace tspfuzz {

/// Reads every step of the mesh input at path (a PLOT3D solution on plot3d_grid) and voxelizes
/// it every way; tsp::Error is a clean refusal, anything else a finding.
inline void voxelize_every_way(const std::string& path, const std::string& plot3d_grid = "") {
  expect_clean([&] {
    auto s = tsp::open_mesh_source(path, "", false, plot3d_grid);
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
}

}  // namespace tspfuzz

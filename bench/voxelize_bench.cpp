// Voxelization throughput on one mesh step: tspplay's voxelizer (cells → tetrahedra → binned,
// sampled) timed over rounds, writing the grid and stencil for bench/voxelize_vtk.py, which
// times VTK's vtkResampleToImage on the same mesh and grid in the same run and compares values.
//   voxelize_bench MESH FIELD RESOLUTION OUT_PREFIX [ROUNDS] [iso|tets|scanK|twoK|twoKj]
// prints JSON: cells, tets, voxels, inside, the grid, seconds per round (median), cells/s,
// voxels/s; writes OUT_PREFIX.f32 (values) and OUT_PREFIX.u8 (stencil), x fastest.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tsp/core/stopwatch.h"
#include "tsp/source/open_mesh_source.h"
#include "tsp/voxelize/voxelized_source.h"

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: voxelize_bench MESH FIELD RESOLUTION OUT_PREFIX [ROUNDS] "
                         "[iso|tets|scanK|twoK|twoKj]\n");
    return 2;
  }
  try {
    const int rounds = argc > 5 ? std::atoi(argv[5]) : 5;
    // iso (default), tets, scanK (voxelizer B with K× anti-aliasing), twoK (voxelizer C, the
    // two-buffer method, K³ passes) or twoKj (jittered).
    const std::string mode = argc > 6 ? argv[6] : "iso";
    tsp::SampleOptions so;
    if (mode == "tets") so.hex = tsp::HexSampling::tetrahedra;
    if (mode.rfind("scan", 0) == 0) {
      so.kind = tsp::VoxelizerKind::scan;
      so.antialias = mode.size() > 4 ? std::atoi(mode.c_str() + 4) : 1;
    }
    if (mode.rfind("two", 0) == 0) {
      so.kind = tsp::VoxelizerKind::two_buffer;
      so.antialias = mode.size() > 3 ? std::max(1, std::atoi(mode.c_str() + 3)) : 1;
      so.jitter = mode.back() == 'j';
    }
    if (so.antialias < 1 || so.antialias > (so.kind == tsp::VoxelizerKind::two_buffer
                                                ? tsp::kMaxTwoBufferK
                                                : tsp::kMaxAntialias)) {
      std::fprintf(stderr, "voxelize_bench: %s: anti-aliasing factor out of range\n", mode.c_str());
      return 2;
    }
    auto source = tsp::open_mesh_source(argv[1], argv[2]);
    const tsp::Mesh mesh = source->read_step(0);
    tsp::VoxelizeOptions o;
    o.resolution = std::atoi(argv[3]);
    const tsp::VoxelGrid grid = tsp::choose_grid(mesh.bounds(), 0, o);
    std::vector<float> values(std::size_t(grid.dims.count()));
    std::vector<std::uint8_t> inside(values.size());
    std::vector<double> seconds;
    tsp::VoxelizeStats st;
    for (int r = 0; r < rounds; ++r) {
      const tsp::Stopwatch w;
      st = tsp::voxelize(mesh, grid, values, inside, so);
      seconds.push_back(w.seconds());
    }
    std::sort(seconds.begin(), seconds.end());
    const double s = seconds[seconds.size() / 2];
    std::ofstream(std::string(argv[4]) + ".f32", std::ios::binary)
        .write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * 4));
    std::ofstream(std::string(argv[4]) + ".u8", std::ios::binary)
        .write(reinterpret_cast<const char*>(inside.data()), std::streamsize(inside.size()));
    nlohmann::json j = {{"cells", mesh.cell_count()},
                        {"tets", st.tets},
                        {"hexahedra_whole", st.hexahedra},
                        {"voxels", grid.dims.count()},
                        {"inside", st.inside},
                        {"dims", {grid.dims.x, grid.dims.y, grid.dims.z}},
                        {"origin", grid.origin},
                        {"spacing", grid.spacing},
                        {"seconds", s},
                        {"cells_per_s", double(mesh.cell_count()) / s},
                        {"voxels_per_s", double(grid.dims.count()) / s}};
    std::printf("%s\n", j.dump().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "voxelize_bench: %s\n", e.what());
    return 1;
  }
}

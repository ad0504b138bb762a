// The committed OpenFOAM sample (datasets/samples/damBreakWithObstacle: hexahedra, polyhedra from
// adaptive refinement, the obstacle's hole, a mesh per step) through the reader and both
// voxelizers: the hole's voxels are outside, the rest of the box inside, values in [0, 1].
#include <gtest/gtest.h>

#include <algorithm>

#include "support/paths.h"
#include "tsp/source/open_mesh_source.h"
#include "tsp/voxelize/voxelized_source.h"

namespace tsp {
namespace {

TEST(OpenFoamSample, PolyhedraAndTheObstacleHole) {
  auto s = open_mesh_source((tsptest::datasets_dir() / "samples" / "damBreakWithObstacle" /
                             "damBreakWithObstacle.vtu.series").string(),
                            "alpha.water");
  ASSERT_EQ(s->steps(), 2);
  EXPECT_EQ(s->times(), (std::vector<double>{0.1, 0.2}));
  VoxelGrid g;  // voxel centres at the 32³ cell centres of the unit box: none on a face
  g.dims = Dims{32, 32, 32};
  g.origin = {1.0 / 64, 1.0 / 64, 1.0 / 64};
  g.spacing = {1.0 / 32, 1.0 / 32, 1.0 / 32};
  std::vector<float> v(std::size_t(g.dims.count()));
  std::vector<std::uint8_t> in(v.size());
  for (int t = 0; t < 2; ++t) {
    const Mesh m = s->read_step(t);
    EXPECT_GT(std::count(m.types.begin(), m.types.end(), CellType::polyhedron), 100);
    SampleOptions iso, scan;
    scan.kind = VoxelizerKind::scan;
    for (const SampleOptions& so : {iso, scan}) {
      voxelize(m, g, v, in, so);
      for (int z = 0; z < 32; ++z)
        for (int y = 0; y < 32; ++y)
          for (int x = 0; x < 32; ++x) {
            const double c[3] = {(x + 0.5) / 32, (y + 0.5) / 32, (z + 0.5) / 32};
            const bool hole = c[0] > 0.375 && c[0] < 0.625 && c[1] > 0.375 && c[1] < 0.625 &&
                              c[2] < 0.25;
            const std::size_t i = std::size_t(x + 32 * (y + 32 * z));
            ASSERT_EQ(in[i], hole ? 0 : 1) << "step " << t << " voxel " << x << "," << y << "," << z;
            EXPECT_GE(v[i], -1e-6f);
            EXPECT_LE(v[i], 1 + 1e-6f);
          }
    }
  }
}

}  // namespace
}  // namespace tsp

// geometric_box: voxel boxes to the closed boxes that tile [0, D − 1]³ with shared faces.
#include "tsp/core/geometry.h"

#include <gtest/gtest.h>

namespace {

TEST(Geometry, InnerBoxesKeepTheirBoundsAndEdgeBoxesStopAtTheLastSample) {
  const tsp::Dims d{33, 17, 9};
  // A brick of samples [0, 17) shares sample 16 with its neighbour: its box is [0, 16].
  EXPECT_EQ(tsp::geometric_box(tsp::Box{{0, 0, 0}, {16, 8, 4}}, d),
            (tsp::Aabb{{0, 0, 0}, {16, 8, 4}}));
  // The last brick's half-open end D is clamped to D − 1.
  EXPECT_EQ(tsp::geometric_box(tsp::Box{{16, 8, 4}, {33, 17, 9}}, d),
            (tsp::Aabb{{16, 8, 4}, {32, 16, 8}}));
  // The whole grid.
  EXPECT_EQ(tsp::geometric_box(tsp::Box{{0, 0, 0}, {33, 17, 9}}, d),
            (tsp::Aabb{{0, 0, 0}, {32, 16, 8}}));
}

TEST(Geometry, NeighboursShareTheirFace) {
  const tsp::Dims d{20, 20, 20};
  const tsp::Aabb lo = tsp::geometric_box(tsp::Box{{0, 0, 0}, {10, 20, 20}}, d);
  const tsp::Aabb hi = tsp::geometric_box(tsp::Box{{10, 0, 0}, {20, 20, 20}}, d);
  EXPECT_EQ(lo.hi[0], 10);
  EXPECT_EQ(hi.lo[0], 10);
  EXPECT_EQ(hi.hi[0], 19);
}

}  // namespace

// Cells to tetrahedra: volumes add up, shared faces are cut the same way from both sides, the
// 5-tet split is taken when the diagonals allow it, polyhedra match their hexahedron.
#include "tsp/voxelize/tetrahedra.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "support/mesh_shapes.h"

namespace tsp {
namespace {

double volume(const TetMesh& m, const std::array<std::int64_t, 4>& t) {
  double e[3][3];
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 3; ++a)
      e[i][a] = m.points[std::size_t(3 * t[std::size_t(i) + 1] + a)] - m.points[std::size_t(3 * t[0] + a)];
  return std::fabs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                   e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                   e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) / 6;
}

using tsptest::hex_box;

TEST(Tetrahedra, HexBoxIsConformingAndFillsItsVolume) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const int n = 4;
    const TetMesh t = tetrahedralize(hex_box(n, seed));
    double v = 0;
    for (const auto& q : t.tets) v += volume(t, q);
    EXPECT_NEAR(v, n * n * n, 1e-9) << seed;
    // Every triangle is shared by exactly two tets inside the box and one on its boundary.
    std::map<std::array<std::int64_t, 3>, int> faces;
    for (const auto& q : t.tets)
      for (int skip = 0; skip < 4; ++skip) {
        std::array<std::int64_t, 3> f;
        int k = 0;
        for (int i = 0; i < 4; ++i)
          if (i != skip) f[std::size_t(k++)] = q[std::size_t(i)];
        std::sort(f.begin(), f.end());
        ++faces[f];
      }
    for (const auto& [f, count] : faces) {
      bool boundary = false;
      for (int a = 0; a < 3; ++a) {
        const double c0 = t.points[std::size_t(3 * f[0] + a)], c1 = t.points[std::size_t(3 * f[1] + a)],
                     c2 = t.points[std::size_t(3 * f[2] + a)];
        boundary |= c0 == c1 && c1 == c2 && (c0 == 0 || c0 == n);
      }
      EXPECT_EQ(count, boundary ? 1 : 2) << "seed " << seed;
    }
  }
}

TEST(Tetrahedra, FiveTetSplitWhenTheDiagonalsAllowIt) {
  // Points 0, 2, 5, 7 (one alternate set) hold the smallest ids: every face's diagonal joins two
  // of them, the 5-tet pattern of paper 000.
  Mesh m = hex_box(1, 1);
  const std::int64_t order[8] = {0, 4, 1, 5, 6, 2, 7, 3};  // local vertex → global id
  std::vector<double> pts(24);
  const double corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int i = 0; i < 8; ++i)
    for (int a = 0; a < 3; ++a) pts[std::size_t(3 * order[i] + a)] = corner[i][a];
  m.points = pts;
  m.connectivity.assign(order, order + 8);
  const TetMesh t = tetrahedralize(m);
  ASSERT_EQ(t.tets.size(), 5u);
  double v = 0;
  for (const auto& q : t.tets) v += volume(t, q);
  EXPECT_NEAR(v, 1.0, 1e-12);
}

TEST(Tetrahedra, WedgePyramidAndPolyhedronFillTheirVolumes) {
  Mesh m;
  m.points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1,  // wedge 0..5
              0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 1};    // pyramid 6..10
  m.connectivity = {3, 4, 5, 0, 1, 2, 6, 7, 8, 9, 10};
  m.offsets = {0, 6, 11};
  m.types = {CellType::wedge, CellType::pyramid};
  m.values.assign(11, 0.f);
  TetMesh t = tetrahedralize(m);
  double wedge = 0, pyramid = 0;
  for (std::size_t i = 0; i < t.tets.size(); ++i) (t.cell[i] ? pyramid : wedge) += volume(t, t.tets[i]);
  EXPECT_NEAR(wedge, 0.5, 1e-12);
  EXPECT_NEAR(pyramid, 1.0 / 3, 1e-12);
  EXPECT_EQ(std::count(t.cell.begin(), t.cell.end(), 0), 3);
  EXPECT_EQ(std::count(t.cell.begin(), t.cell.end(), 1), 2);

  // A cube as a polyhedron: its centroid fan has the cube's volume, a centroid valued at the
  // mean of its points.
  Mesh h = hex_box(1, 3);
  for (std::int64_t p = 0; p < 8; ++p) h.values[std::size_t(p)] = float(p);
  Mesh poly = h;
  poly.types = {CellType::polyhedron};
  const std::int64_t* g = h.connectivity.data();
  poly.face_start = {0};
  poly.faces = {6};
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (const auto& f : faces) {
    poly.faces.push_back(4);
    for (int i : f) poly.faces.push_back(g[i]);
  }
  check_mesh(poly, "poly");
  t = tetrahedralize(poly);
  EXPECT_EQ(t.tets.size(), 12u);
  double v = 0;
  for (const auto& q : t.tets) v += volume(t, q);
  EXPECT_NEAR(v, 1.0, 1e-12);
  ASSERT_EQ(t.values.size(), 9u);
  EXPECT_FLOAT_EQ(t.values[8], 3.5f);
}

TEST(Tetrahedra, CellDataAveragedToPoints) {
  Mesh m = hex_box(2, 4);
  m.cell_values = true;
  m.values = {1, 2, 3, 4, 5, 6, 7, 8};
  const std::vector<float> p = cell_values_to_points(m);
  // The box's centre point (1,1,1) touches all eight cells.
  for (std::int64_t i = 0; i < m.point_count(); ++i)
    if (m.points[std::size_t(3 * i)] == 1 && m.points[std::size_t(3 * i + 1)] == 1 &&
        m.points[std::size_t(3 * i + 2)] == 1)
      EXPECT_FLOAT_EQ(p[std::size_t(i)], 4.5f);
}

}  // namespace
}  // namespace tsp

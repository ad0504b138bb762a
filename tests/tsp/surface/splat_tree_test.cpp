// A mesh's boundary and TetSplat's splat hierarchy over it, against analytic shapes: the faces of
// an n³ box of hexahedra (and of single cells of each type) cover its six sides once, outwards;
// the hierarchy's sums (area, area-weighted field) and its cuts cover every leaf exactly once.
#include "tsp/surface/boundary.h"
#include "tsp/surface/splat_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/mesh_shapes.h"

namespace tsp {
namespace {

using tsptest::hex_box;

std::array<double, 3> at(const Mesh& m, std::int64_t i) {
  return {m.points[std::size_t(3 * i)], m.points[std::size_t(3 * i + 1)], m.points[std::size_t(3 * i + 2)]};
}

// Area and unit normal of a triangle.
std::array<double, 4> area_normal(const Mesh& m, const std::array<std::int64_t, 3>& t) {
  const auto a = at(m, t[0]), b = at(m, t[1]), c = at(m, t[2]);
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double len = std::hypot(n[0], n[1], n[2]);
  return {0.5 * len, n[0] / len, n[1] / len, n[2] / len};
}

// The boundary of an n³ box covers its 6 sides (area 6n²) with axis-aligned outward triangles.
void expect_box_boundary(const Mesh& m, int n) {
  const BoundaryTriangles b = boundary_triangles(m);
  ASSERT_EQ(b.points.size(), std::size_t(12 * n * n));
  double area = 0;
  std::array<double, 6> side{};  // area per side: −x, +x, −y, +y, −z, +z
  for (const auto& t : b.points) {
    const auto an = area_normal(m, t);
    area += an[0];
    int axis = -1;
    for (int a = 0; a < 3; ++a)
      if (std::fabs(std::fabs(an[std::size_t(a) + 1]) - 1) < 1e-12) axis = a;
    ASSERT_GE(axis, 0) << "not axis-aligned";
    const double coord = at(m, t[0])[std::size_t(axis)];
    for (int k = 1; k < 3; ++k) EXPECT_EQ(at(m, t[std::size_t(k)])[std::size_t(axis)], coord);
    const double sign = an[std::size_t(axis) + 1];
    // On the side it faces: coordinate 0 facing −, n facing +.
    EXPECT_EQ(coord, sign > 0 ? n : 0) << "inner face or facing inwards";
    side[std::size_t(2 * axis + (sign > 0 ? 1 : 0))] += an[0];
  }
  EXPECT_NEAR(area, 6.0 * n * n, 1e-9);
  for (double s : side) EXPECT_NEAR(s, double(n) * n, 1e-9);
}

TEST(Boundary, HexBoxFacesCoverItsSixSidesOnceFacingOut) {
  for (unsigned seed = 1; seed <= 3; ++seed) expect_box_boundary(hex_box(3, seed), 3);
  expect_box_boundary(hex_box(1, 7), 1);
}

TEST(Boundary, EachCellTypeAloneIsItsOwnBoundary) {
  // A unit voxel (VTK's x-fastest corner order) and the unit cube as five tetrahedra.
  Mesh v;
  for (int i = 0; i < 8; ++i)
    for (int a = 0; a < 3; ++a) v.points.push_back((i >> a) & 1);
  v.offsets = {0, 8};
  v.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  v.types = {CellType::voxel};
  v.values.assign(8, 0.f);
  check_mesh(v, "voxel");
  expect_box_boundary(v, 1);

  Mesh t = v;
  t.types.assign(5, CellType::tetra);
  t.connectivity = {0, 1, 2, 4, 1, 3, 2, 7, 1, 4, 5, 7, 2, 4, 7, 6, 1, 2, 4, 7};
  t.offsets = {0, 4, 8, 12, 16, 20};
  check_mesh(t, "five tets");
  expect_box_boundary(t, 1);  // the middle tetrahedron's faces are all shared

  // A wedge (triangular prism) of unit legs and height: 2 triangles of ½, 3 sides 1, 1, √2.
  Mesh w;
  w.points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1};
  w.offsets = {0, 6};
  w.connectivity = {0, 1, 2, 3, 4, 5};
  w.types = {CellType::wedge};
  w.values.assign(6, 0.f);
  check_mesh(w, "wedge");
  const BoundaryTriangles bw = boundary_triangles(w);
  EXPECT_EQ(bw.points.size(), 8u);
  double area = 0;
  for (const auto& tri : bw.points) {
    const auto an = area_normal(w, tri);
    area += an[0];
    // Outwards: from the prism's centroid (1/3, 1/3, 1/2) to the triangle.
    const auto p = at(w, tri[0]);
    EXPECT_GT(an[1] * (p[0] - 1.0 / 3) + an[2] * (p[1] - 1.0 / 3) + an[3] * (p[2] - 0.5), 0);
  }
  EXPECT_NEAR(area, 1 + 2 + std::sqrt(2.0), 1e-12);
}

TEST(SplatTree, SumsOverTheBoundaryAndCutsCoverEveryLeafOnce) {
  const Mesh m = hex_box(4, 5);
  const BoundaryTriangles b = boundary_triangles(m);
  // Samples every half unit from −1: sample coordinates (p + 1) / 0.5.
  const SplatTree tree = build_splat_tree(m, b, {-1, -1, -1}, {0.5, 0.5, 0.5});
  ASSERT_EQ(tree.leaves, int(b.points.size()));
  ASSERT_EQ(tree.nodes.size(), std::size_t(2 * tree.leaves - 1));
  const SurfaceSplat& root = tree.nodes[0].splat;
  EXPECT_NEAR(root.area, 6 * 16 * 4, 1e-3);  // 96 unit squares, 4 sample units² each
  // The area-weighted mean of x over the box's surface is 2 (symmetry), the centre (2,2,2) →
  // sample coordinates (6,6,6).
  EXPECT_NEAR(root.value, 2.0, 1e-5);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(root.centre[std::size_t(k)], 6.0, 1e-5);
  EXPECT_EQ(tree.value_range, (ValueRange{0, 4}));
  // Every node before its children, its radius holding theirs; a leaf keeps its triangle,
  // centred on its splat and held by its radius.
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    const SplatTreeNode& n = tree.nodes[i];
    if (n.is_leaf()) {
      for (std::size_t k = 0; k < 3; ++k)
        EXPECT_NEAR((n.triangle[0][k] + n.triangle[1][k] + n.triangle[2][k]) / 3, n.splat.centre[k], 1e-5);
      for (const auto& c : n.triangle)
        EXPECT_LE(std::hypot(double(c[0]) - n.splat.centre[0], double(c[1]) - n.splat.centre[1],
                             double(c[2]) - n.splat.centre[2]),
                  n.splat.radius * (1 + 1e-6) + 1e-6);
      continue;
    }
    for (int c : n.child) {
      ASSERT_GT(c, int(i));
      const SurfaceSplat& s = tree.nodes[std::size_t(c)].splat;
      const double d = std::hypot(double(s.centre[0]) - n.splat.centre[0],
                                  double(s.centre[1]) - n.splat.centre[1],
                                  double(s.centre[2]) - n.splat.centre[2]);
      EXPECT_LE(d + s.radius, n.splat.radius * (1 + 1e-6) + 1e-6);
    }
  }
  // Cuts: every leaf below exactly one cut node; fewer nodes as the minimum grows.
  CameraParams p;
  p.width = 400;
  p.height = 300;
  const Camera camera({20, 20, 20}, p);
  std::size_t previous = std::size_t(tree.leaves) + 1;
  for (double px : {0.0, 2.0, 8.0, 32.0, 128.0, 1e6}) {
    const std::vector<int> cut = splat_surface_cut(tree, camera, px);
    EXPECT_LE(cut.size(), previous);
    previous = cut.size();
    double area = 0;
    for (int id : cut) {
      area += tree.nodes[std::size_t(id)].splat.area;
      if (!tree.nodes[std::size_t(id)].is_leaf()) {
        EXPECT_LE(projected_diameter(camera, tree.nodes[std::size_t(id)].splat), px);
      }
    }
    EXPECT_NEAR(area, root.area, 1e-2) << px;
    if (px == 0.0) {
      EXPECT_EQ(cut.size(), std::size_t(tree.leaves));
    }
    if (px == 1e6) {
      EXPECT_EQ(cut, std::vector<int>{0});
    }
  }
}

TEST(SplatTree, ProjectedDiameterFollowsTheOrthographicScale) {
  // Orthographic: the diameter is twice the distance in pixels between the projections of the
  // splat's centre and of a point on its rim across the view.
  CameraParams p;
  p.width = 300;
  p.height = 300;
  const Camera camera({33, 33, 33}, p);
  SurfaceSplat s;
  s.centre = {16, 16, 16};
  s.radius = 4;
  const glm::dmat4 vp = camera.view_projection();
  // A point on the rim, perpendicular to the view: the view's x axis in sample coordinates.
  const glm::dmat4 inv = glm::inverse(camera.view());
  const glm::dvec3 right = glm::normalize(glm::dvec3(inv[0]));
  const glm::dvec4 c = vp * glm::dvec4(16, 16, 16, 1), e = vp * glm::dvec4(glm::dvec3(16) + 4.0 * right, 1);
  const double px = std::fabs(e.x / e.w - c.x / c.w) * 0.5 * p.width;
  EXPECT_NEAR(projected_diameter(camera, s), 2 * px, 1e-9 * px);
}

TEST(SplatTree, CellValuesAndDegenerateTriangles) {
  Mesh m = hex_box(2, 9);
  m.cell_values = true;
  m.values = {1, 2, 3, 4, 5, 6, 7, 8};
  const SplatTree tree = build_splat_tree(m, boundary_triangles(m), {0, 0, 0}, {1, 1, 1});
  // Every cell of a 2³ box touches the boundary with 3 unit squares: the mean is 4.5.
  EXPECT_NEAR(tree.nodes[0].splat.value, 4.5, 1e-5);
  EXPECT_EQ(tree.value_range, (ValueRange{1, 8}));
  // A flattened tetrahedron has no area: nothing to draw.
  Mesh flat;
  flat.points = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0};
  flat.offsets = {0, 4};
  flat.connectivity = {0, 1, 2, 3};
  flat.types = {CellType::tetra};
  flat.values.assign(4, 0.f);
  const SplatTree none = build_splat_tree(flat, boundary_triangles(flat), {0, 0, 0}, {1, 1, 1});
  EXPECT_EQ(none.leaves, 0);
  EXPECT_TRUE(none.nodes.empty());
  EXPECT_TRUE(splat_surface_cut(none, Camera({4, 4, 4}, CameraParams{}), 1).empty());
}

}  // namespace
}  // namespace tsp

#include "tsp/frame/camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tsp/core/error.h"

namespace tsp {
namespace {

glm::dvec3 project(const Camera& c, glm::dvec3 p) {
  glm::dvec4 clip = c.view_projection() * glm::dvec4(p, 1.0);
  return glm::dvec3(clip) / clip.w;
}

std::array<glm::dvec3, 8> corners(Dims d) {
  std::array<glm::dvec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[i] = {(i & 1) ? d.x - 1.0 : 0.0, (i & 2) ? d.y - 1.0 : 0.0, (i & 4) ? d.z - 1.0 : 0.0};
  return c;
}

TEST(Camera, FrontViewLooksAlongPlusYWithZUp) {
  CameraParams p;
  p.azimuth_deg = 0;
  p.elevation_deg = 0;
  Camera c({11, 21, 31}, p);
  auto d = c.direction();
  EXPECT_NEAR(d[0], 0, 1e-12);
  EXPECT_NEAR(d[1], 1, 1e-12);
  EXPECT_NEAR(d[2], 0, 1e-12);
  // +x is to the right and +z is up on screen.
  glm::dvec3 centre(5, 10, 15);
  EXPECT_GT(project(c, centre + glm::dvec3(1, 0, 0)).x, project(c, centre).x);
  EXPECT_GT(project(c, centre + glm::dvec3(0, 0, 1)).y, project(c, centre).y);
  EXPECT_NEAR(project(c, centre).x, 0, 1e-12);
  EXPECT_NEAR(project(c, centre).y, 0, 1e-12);
}

TEST(Camera, DirectionMatchesEyeToCentreAndAnglesForBothProjections) {
  for (Projection proj : {Projection::orthographic, Projection::perspective}) {
    for (double az : {0.0, 37.0, 90.0, 200.0, -45.0})
      for (double el : {-60.0, 0.0, 25.0, 80.0}) {
        CameraParams p;
        p.azimuth_deg = az;
        p.elevation_deg = el;
        p.projection = proj;
        Camera c({64, 32, 16}, p);
        auto d = c.direction();
        auto e = c.eye();
        glm::dvec3 centre(31.5, 15.5, 7.5);
        glm::dvec3 to_centre = glm::normalize(centre - glm::dvec3(e[0], e[1], e[2]));
        EXPECT_NEAR(to_centre.x, d[0], 1e-9);
        EXPECT_NEAR(to_centre.y, d[1], 1e-9);
        EXPECT_NEAR(to_centre.z, d[2], 1e-9);
        // Elevation is the angle above the x-y plane, seen from the eye side.
        EXPECT_NEAR(std::asin(-d[2]) * 180 / 3.14159265358979323846, el, 1e-9);
        // The whole volume is inside the view volume at zoom 1.
        for (auto q : corners({64, 32, 16})) {
          glm::dvec3 n = project(c, q);
          EXPECT_LE(std::fabs(n.x), 1.0 + 1e-9);
          EXPECT_LE(std::fabs(n.y), 1.0 + 1e-9);
          EXPECT_LE(std::fabs(n.z), 1.0 + 1e-9);
        }
      }
  }
}

// Anisotropic voxels: a grid of 11×21×31 samples with voxels 3×1×2 is the same box as a
// 31×21×61 grid of cubes, point for point: sample (i, j, k) lands where (3i, j, 2k) does. The
// orthographic rays run along the eye's direction divided by the stretch; slice planes are
// normal to it multiplied by the stretch; the eye maps back through the stretch.
TEST(Camera, StretchedVoxelsProjectLikeTheStretchedGridOfCubes) {
  for (Projection proj : {Projection::orthographic, Projection::perspective})
    for (double az : {0.0, 37.0, 200.0})
      for (double el : {-40.0, 0.0, 25.0}) {
        CameraParams p;
        p.azimuth_deg = az;
        p.elevation_deg = el;
        p.projection = proj;
        p.pan = {0.1, -0.2};
        CameraParams cubes = p;
        p.voxel_size = {6, 2, 4};  // (any scale: the smallest axis becomes 1)
        const Camera stretched({11, 21, 31}, p), plain({31, 21, 61}, cubes);
        const glm::dvec3 s(3, 1, 2);
        for (glm::dvec3 q : {glm::dvec3(0, 0, 0), glm::dvec3(10, 20, 30), glm::dvec3(2.5, 7, 11)}) {
          const glm::dvec3 a = project(stretched, q), b = project(plain, q * s);
          EXPECT_NEAR(a.x, b.x, 1e-9);
          EXPECT_NEAR(a.y, b.y, 1e-9);
          EXPECT_NEAR(a.z, b.z, 1e-9);
        }
        const auto e = stretched.eye(), ep = plain.eye();
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(e[i] * s[i], ep[i], 1e-9);
        const auto d = plain.direction(), r = stretched.ray_direction(), n = stretched.direction();
        const glm::dvec3 ray = glm::normalize(glm::dvec3(d[0], d[1], d[2]) / s);
        const glm::dvec3 normal = glm::normalize(glm::dvec3(d[0], d[1], d[2]) * s);
        for (int i = 0; i < 3; ++i) {
          EXPECT_NEAR(r[i], ray[i], 1e-12);
          EXPECT_NEAR(n[i], normal[i], 1e-12);
        }
        EXPECT_NEAR(stretched.ray_cosine(), glm::dot(ray, normal), 1e-12);
        if (az != 0 || el != 0) EXPECT_LT(stretched.ray_cosine(), 1.0);  // (along y: s_y = 1)
        // Cubes: rays and plane normals agree.
        EXPECT_DOUBLE_EQ(plain.ray_cosine(), 1.0);
      }
}

TEST(Camera, ZoomScalesTheImageAboutTheCentre) {
  CameraParams p;
  Camera a({50, 50, 50}, p);
  p.zoom = 2;
  Camera b({50, 50, 50}, p);
  glm::dvec3 q(40, 10, 30);
  EXPECT_NEAR(project(b, q).x, 2 * project(a, q).x, 1e-9);
  EXPECT_NEAR(project(b, q).y, 2 * project(a, q).y, 1e-9);
}

TEST(Camera, ScreenFootprintBoundsTheProjectedCornersAndCullsWhatIsOutside) {
  const Dims d{33, 33, 33};
  CameraParams p;
  p.width = 200;
  p.height = 100;
  const Camera cam(d, p);
  const Aabb all{{0, 0, 0}, {32, 32, 32}};
  const ScreenFootprint f = screen_footprint(cam, all);
  EXPECT_FALSE(f.culled);
  EXPECT_FALSE(f.behind);
  for (const glm::dvec3& c : corners(d)) {  // every corner inside the rectangle, some on its edges
    const glm::dvec3 n = project(cam, c);
    const double x = (n.x * 0.5 + 0.5) * 200, y = (n.y * 0.5 + 0.5) * 100;
    EXPECT_GE(x, f.rect[0] - 1e-9);
    EXPECT_LE(x, f.rect[2] + 1e-9);
    EXPECT_GE(y, f.rect[1] - 1e-9);
    EXPECT_LE(y, f.rect[3] + 1e-9);
  }
  EXPECT_GT(f.rect[2] - f.rect[0], 50);  // the fitted view shows the volume large
  // A box far to the side is outside the frustum.
  EXPECT_TRUE(screen_footprint(cam, Aabb{{1000, 0, 0}, {1010, 10, 10}}).culled);
  // Perspective, a box around the eye: corners behind it, so the whole image.
  CameraParams q = p;
  q.projection = Projection::perspective;
  const Camera persp(d, q);
  const auto e = persp.eye();
  const ScreenFootprint g =
      screen_footprint(persp, Aabb{{e[0] - 5, e[1] - 5, e[2] - 5}, {e[0] + 5, e[1] + 5, e[2] + 5}});
  EXPECT_TRUE(g.behind);
  EXPECT_EQ(g.rect, (std::array<double, 4>{0, 0, 200, 100}));
}

TEST(Camera, ParsesViewAnglesAndRejectsBadText) {
  auto v = parse_view_angles("30,-20.5");
  EXPECT_EQ(v[0], 30);
  EXPECT_EQ(v[1], -20.5);
  for (const char* bad : {"", "30", "a,b", "30,90", "30,-90", "1,2,3", "nan,1"})
    EXPECT_THROW(parse_view_angles(bad), UsageError) << bad;
}

}  // namespace
}  // namespace tsp

namespace tsp {
namespace {

// Two fields on different grids (W: one more level, half a layer lower, stretched voxels) fitted
// to one frame: a physical point projects to the same pixel and depth in both views; each view
// fitted to its own box would put it elsewhere.
TEST(Camera, FieldsSharingAFrameProjectAPhysicalPointAlike) {
  CameraParams p;
  p.width = 320;
  p.height = 200;
  p.azimuth_deg = 35;
  p.elevation_deg = 25;
  p.voxel_size = {2, 2, 0.5};
  const Dims t_dims{16, 12, 9}, w_dims{16, 12, 10};
  CameraParams t = p, w = p;
  w.origin = {-3, 0, -0.25};  // half a layer of 0.5 lower, and 1.5 voxels to the left
  t.frame = w.frame = Aabb{{-3, 0, -0.25}, {30, 22, 4.25}};
  for (Projection proj : {Projection::orthographic, Projection::perspective}) {
    t.projection = w.projection = proj;
    const Camera ct(t_dims, t), cw(w_dims, w);
    for (const glm::dvec3 phys : {glm::dvec3(3, 4, 1), glm::dvec3(28, 2, 3.5), glm::dvec3(15, 11, 0)}) {
      // Sample coordinates: (phys − origin) / voxel size.
      const glm::dvec3 st = phys / glm::dvec3(2, 2, 0.5);
      const glm::dvec3 sw = (phys - glm::dvec3(-3, 0, -0.25)) / glm::dvec3(2, 2, 0.5);
      const glm::dvec4 a = ct.view_projection() * glm::dvec4(st, 1.0);
      const glm::dvec4 b = cw.view_projection() * glm::dvec4(sw, 1.0);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k] / a.w, b[k] / b.w, 1e-9) << k;
      // The eye, in each volume's sample coordinates, is the same physical point.
      const auto vec = [](std::array<double, 3> e) { return glm::dvec3(e[0], e[1], e[2]); };
      const glm::dvec3 et = vec(ct.eye()) * glm::dvec3(2, 2, 0.5);
      const glm::dvec3 ew = vec(cw.eye()) * glm::dvec3(2, 2, 0.5) + glm::dvec3(-3, 0, -0.25);
      EXPECT_NEAR(glm::length(et - ew), 0, 1e-9);
    }
    // Fitted each to its own box, the two views disagree.
    CameraParams own_t = t, own_w = w;
    own_t.frame = own_w.frame = empty_aabb();
    own_w.origin = {0, 0, 0};
    const glm::dvec4 a = Camera(t_dims, own_t).view_projection() * glm::dvec4(1, 1, 1, 1.0);
    const glm::dvec4 b = Camera(w_dims, own_w).view_projection() * glm::dvec4(2.5, 1, 1.5, 1.0);
    EXPECT_GT(glm::length(glm::dvec2(a) / a.w - glm::dvec2(b) / b.w), 0.02);
  }
}

}  // namespace
}  // namespace tsp

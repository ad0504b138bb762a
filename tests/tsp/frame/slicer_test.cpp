#include "tsp/frame/slicer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/frame/naive_slicer.h"

namespace tsp {
namespace {

using Vec = std::array<double, 3>;

struct Poly {
  std::int64_t plane = 0;
  std::vector<Vec> v;
};

std::vector<Poly> polygons(const PolygonSoup& s) {
  std::vector<Poly> out;
  std::size_t at = 0;
  EXPECT_EQ(s.counts.size(), s.planes.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    Poly p;
    p.plane = s.planes[i];
    for (int j = 0; j < s.counts[i]; ++j, ++at)
      p.v.push_back({s.xyz[3 * at], s.xyz[3 * at + 1], s.xyz[3 * at + 2]});
    out.push_back(p);
  }
  EXPECT_EQ(at, s.vertex_count());
  return out;
}

std::vector<Poly> incremental(const SlicePlanes& planes, const Aabb& box) {
  PolygonSoup s;
  IncrementalSlicer(planes).slice(box, s);
  return polygons(s);
}

std::vector<Poly> naive(const SlicePlanes& planes, const Aabb& box) {
  PolygonSoup s;
  naive_slice(planes, box, s);
  return polygons(s);
}

Vec sub(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double dist(const Vec& a, const Vec& b) {
  return std::sqrt(dot(sub(a, b), sub(a, b)));
}

// Area seen from the eye: positive for counter-clockwise polygons.
double area(const Poly& p, const Vec& dir) {
  double twice = 0;
  for (std::size_t i = 1; i + 1 < p.v.size(); ++i)
    twice -= dot(cross(sub(p.v[i], p.v[0]), sub(p.v[i + 1], p.v[0])), dir);
  return twice / 2;
}

double max_extent(const Aabb& b) {
  return std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
}

// Same polygons in the same order, vertex lists equal up to a rotation, within tol.
::testing::AssertionResult same_polygons(const std::vector<Poly>& a, const std::vector<Poly>& b,
                                         double tol) {
  if (a.size() != b.size())
    return ::testing::AssertionFailure() << a.size() << " vs " << b.size() << " polygons";
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].plane != b[i].plane || a[i].v.size() != b[i].v.size())
      return ::testing::AssertionFailure()
             << "polygon " << i << ": plane " << a[i].plane << " vs " << b[i].plane << ", "
             << a[i].v.size() << " vs " << b[i].v.size() << " vertices";
    const std::size_t n = a[i].v.size();
    bool found = false;
    for (std::size_t r = 0; r < n && !found; ++r) {
      bool all = true;
      for (std::size_t j = 0; j < n && all; ++j) all = dist(a[i].v[j], b[i].v[(j + r) % n]) <= tol;
      found = all;
    }
    if (!found) return ::testing::AssertionFailure() << "polygon " << i << " differs";
  }
  return ::testing::AssertionSuccess();
}

// Checks that need no second slicer: planes strictly back to front and within the box's depth
// range, every vertex on its plane and on an edge of the box, polygons of 3..6 distinct vertices,
// convex and counter-clockwise from the eye.
::testing::AssertionResult valid_geometry(const SlicePlanes& planes, const Aabb& box,
                                          const std::vector<Poly>& polys) {
  const double size = max_extent(box), tol = 1e-9 * std::max(1.0, size);
  double dmin = 1e300, dmax = -1e300;
  for (int c = 0; c < 8; ++c) {
    const Vec p{c & 1 ? box.hi[0] : box.lo[0], c & 2 ? box.hi[1] : box.lo[1],
                c & 4 ? box.hi[2] : box.lo[2]};
    dmin = std::min(dmin, dot(p, planes.dir));
    dmax = std::max(dmax, dot(p, planes.dir));
  }
  for (std::size_t i = 0; i < polys.size(); ++i) {
    const Poly& p = polys[i];
    const double depth = (double(p.plane) + 0.5) * planes.spacing;
    auto fail = [&]() { return ::testing::AssertionFailure() << "polygon " << i << ": "; };
    if (i > 0 && !(p.plane < polys[i - 1].plane)) return fail() << "not back to front";
    if (depth < dmin - tol || depth > dmax + tol) return fail() << "plane outside the box";
    if (p.v.size() < 3 || p.v.size() > 6) return fail() << p.v.size() << " vertices";
    const std::size_t n = p.v.size();
    for (std::size_t j = 0; j < n; ++j) {
      const Vec& v = p.v[j];
      if (std::abs(dot(v, planes.dir) - depth) > tol) return fail() << "vertex off its plane";
      int on_bound = 0;
      for (int a = 0; a < 3; ++a) {
        if (v[a] < box.lo[a] - tol || v[a] > box.hi[a] + tol) return fail() << "vertex outside";
        if (std::abs(v[a] - box.lo[a]) <= tol || std::abs(v[a] - box.hi[a]) <= tol) ++on_bound;
      }
      if (on_bound < 2) return fail() << "vertex not on a box edge";
      if (dist(v, p.v[(j + 1) % n]) <= 1e-12) return fail() << "duplicate vertex";
      const Vec e1 = sub(p.v[(j + 1) % n], v), e2 = sub(p.v[(j + 2) % n], p.v[(j + 1) % n]);
      if (dot(cross(e1, e2), planes.dir) > tol * size) return fail() << "not convex and ccw";
    }
    if (!(area(p, planes.dir) > 0)) return fail() << "area not positive";
  }
  return ::testing::AssertionSuccess();
}

// ---- random views, boxes and spacings -------------------------------------------------------

std::vector<Vec> special_directions() {
  std::vector<Vec> dirs;
  for (int a = 0; a < 3; ++a)
    for (double s : {1.0, -1.0}) {
      Vec d{0, 0, 0};
      d[a] = s;
      dirs.push_back(d);
    }
  for (int a = 0; a < 3; ++a)  // face diagonals: two non-zero components
    for (double s : {1.0, -1.0})
      for (double t : {1.0, -1.0}) {
        Vec d{0, 0, 0};
        d[a] = s;
        d[(a + 1) % 3] = t;
        dirs.push_back(d);
      }
  for (int m = 0; m < 8; ++m)
    dirs.push_back({m & 1 ? -1.0 : 1.0, m & 2 ? -1.0 : 1.0, m & 4 ? -1.0 : 1.0});
  return dirs;
}

Vec random_direction(std::mt19937& rng, int kind) {
  std::normal_distribution<double> g(0, 1);
  static const std::vector<Vec> special = special_directions();
  std::uniform_int_distribution<std::size_t> pick(0, special.size() - 1);
  switch (kind) {
    case 0:  // uniform on the sphere
      return {g(rng), g(rng), g(rng)};
    case 1:  // exactly an axis or a diagonal
      return special[pick(rng)];
    default: {  // an axis or diagonal tilted by 1e-2 .. 1e-6, or by 1e-15 .. 1e-19, which
                // rounding turns into ties between corner depths in some places but not others
      Vec d = special[pick(rng)];
      const int exponent = std::uniform_int_distribution<int>(0, 1)(rng)
                               ? std::uniform_int_distribution<int>(2, 6)(rng)
                               : std::uniform_int_distribution<int>(15, 19)(rng);
      const double eps = std::pow(10.0, -exponent);
      for (double& x : d) x += eps * g(rng);
      return d;
    }
  }
}

Aabb random_box(std::mt19937& rng) {
  std::uniform_int_distribution<int> coin(0, 1), ilo(-20, 20), isize(1, 40);
  std::uniform_real_distribution<double> rlo(-20, 20), rsize(1, 40);
  Aabb b;
  const bool integer = coin(rng);
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = integer ? ilo(rng) : rlo(rng);
    b.hi[a] = b.lo[a] + (integer ? isize(rng) : rsize(rng));
  }
  return b;
}

double random_spacing(std::mt19937& rng) {
  static const double fixed[] = {0.5, 1.0, 0.25, 2.0 / 3.0};
  std::uniform_int_distribution<int> pick(0, 4);
  const int i = pick(rng);
  return i < 4 ? fixed[i] : std::uniform_real_distribution<double>(0.2, 3.0)(rng);
}

TEST(Slicer, MatchesNaiveForRandomViewsBoxesAndSpacings) {
  std::mt19937 rng(20240601);
  constexpr int kCases = 4000;
  std::size_t total = 0;
  for (int i = 0; i < kCases; ++i) {
    const SlicePlanes planes =
        SlicePlanes::toward(random_direction(rng, i % 3), random_spacing(rng));
    const Aabb box = random_box(rng);
    const auto inc = incremental(planes, box), nai = naive(planes, box);
    const double tol = 1e-9 * max_extent(box);
    ASSERT_TRUE(same_polygons(inc, nai, tol))
        << "case " << i << " dir " << planes.dir[0] << "," << planes.dir[1] << "," << planes.dir[2]
        << " spacing " << planes.spacing;
    ASSERT_TRUE(valid_geometry(planes, box, inc)) << "case " << i;
    total += inc.size();
  }
  EXPECT_GT(total, std::size_t(kCases) * 10);  // the cases really slice something
}

// Planes through corners and edges on purpose: body and face diagonals of integer boxes with a
// spacing that is a fraction of a corner step, so plane depths coincide with corner depths.
TEST(Slicer, MatchesNaiveWhenPlanesPassThroughCornersAndEdges) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> lo(-5, 5), size(1, 6), div(1, 4);
  for (const Vec& raw : special_directions()) {
    const SlicePlanes unit = SlicePlanes::toward(raw, 1);
    double step = 0;  // depth difference between neighbouring integer corners
    for (double x : unit.dir) step = std::max(step, std::abs(x));
    for (int i = 0; i < 60; ++i) {
      const SlicePlanes planes{unit.dir, 2 * step / div(rng)};
      Aabb box;
      for (int a = 0; a < 3; ++a) {
        box.lo[a] = lo(rng);
        box.hi[a] = box.lo[a] + size(rng);
      }
      const auto inc = incremental(planes, box);
      ASSERT_TRUE(same_polygons(inc, naive(planes, box), 1e-9 * max_extent(box)));
      ASSERT_TRUE(valid_geometry(planes, box, inc));
    }
  }
}

// ---- analytic cases --------------------------------------------------------------------------

TEST(Slicer, AxisViewOfIntegerCubeGivesItsSquaresBackToFront) {
  const SlicePlanes planes = SlicePlanes::toward({1, 0, 0}, 0.5);
  const Aabb box{{0, 0, 0}, {4, 3, 2}};
  const auto polys = incremental(planes, box);
  ASSERT_EQ(polys.size(), 8u);  // planes at x = 0.25, 0.75, …, 3.75
  for (std::size_t i = 0; i < polys.size(); ++i) {
    const double x = 3.75 - 0.5 * double(i);
    EXPECT_EQ(polys[i].plane, 7 - std::int64_t(i));
    ASSERT_EQ(polys[i].v.size(), 4u);
    for (const Vec& v : polys[i].v) {
      EXPECT_EQ(v[0], x);
      EXPECT_TRUE(v[1] == 0 || v[1] == 3);
      EXPECT_TRUE(v[2] == 0 || v[2] == 2);
    }
    EXPECT_DOUBLE_EQ(area(polys[i], planes.dir), 6.0);
  }
  // Counter-clockwise from an eye looking along +x: every turn's cross product points back
  // towards the eye (−x).
  const auto& v = polys[0].v;
  for (std::size_t j = 0; j < 4; ++j)
    EXPECT_LT(cross(sub(v[(j + 1) % 4], v[j]), sub(v[(j + 2) % 4], v[(j + 1) % 4]))[0], 0);
}

TEST(Slicer, PlaneThroughThreeCornersOfBodyDiagonalGivesTheTriangle) {
  const SlicePlanes unit = SlicePlanes::toward({1, 1, 1}, 1);
  const double dx = unit.dir[0];
  // Plane 0 at depth dx passes through (1,0,0), (0,1,0), (0,0,1); plane 1 at 3·dx touches only
  // the far corner (1,1,1): a point, dropped.
  const SlicePlanes planes{unit.dir, 2 * dx};
  const Aabb box{{0, 0, 0}, {1, 1, 1}};
  for (const auto& polys : {incremental(planes, box), naive(planes, box)}) {
    ASSERT_EQ(polys.size(), 1u);
    EXPECT_EQ(polys[0].plane, 0);
    ASSERT_EQ(polys[0].v.size(), 3u);
    std::vector<Vec> got = polys[0].v;
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, (std::vector<Vec>{{0, 0, 1}, {0, 1, 0}, {1, 0, 0}}));
    EXPECT_GT(area(polys[0], planes.dir), 0);
  }
}

TEST(Slicer, PlaneThroughTwoEdgesOfFaceDiagonalGivesTheRectangle) {
  const SlicePlanes unit = SlicePlanes::toward({1, 1, 0}, 1);
  const SlicePlanes planes{unit.dir, 2 * unit.dir[0]};  // plane 0 through x + y = 1
  const Aabb box{{0, 0, 0}, {1, 1, 1}};
  for (const auto& polys : {incremental(planes, box), naive(planes, box)}) {
    ASSERT_EQ(polys.size(), 1u);  // plane 1 holds only the far edge x = y = 1: a segment
    ASSERT_EQ(polys[0].v.size(), 4u);
    std::vector<Vec> got = polys[0].v;
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, (std::vector<Vec>{{0, 1, 0}, {0, 1, 1}, {1, 0, 0}, {1, 0, 1}}));
    EXPECT_NEAR(area(polys[0], planes.dir), std::sqrt(2.0), 1e-12);
  }
}

TEST(Slicer, PlaneOnAFaceBelongsToTheNearerBoxOnly) {
  const SlicePlanes planes = SlicePlanes::toward({1, 0, 0}, 0.5);
  const Aabb nearer{{0, 0, 0}, {1.75, 1, 1}}, farther{{1.75, 0, 0}, {3, 1, 1}};
  const auto a = incremental(planes, nearer), b = incremental(planes, farther);
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a.front().plane, 3);  // depth 1.75 = the nearer box's far face: its own
  for (const Vec& v : a.front().v) EXPECT_EQ(v[0], 1.75);
  ASSERT_FALSE(b.empty());
  EXPECT_EQ(b.back().plane, 4);  // … and not the farther box's
  EXPECT_EQ(a.size() + b.size(), incremental(planes, Aabb{{0, 0, 0}, {3, 1, 1}}).size());
}

TEST(Slicer, DegenerateBoxesGiveNothing) {
  const SlicePlanes planes = SlicePlanes::toward({0.3, 0.5, 0.8}, 0.5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Aabb& box : {Aabb{{0, 0, 0}, {4, 4, 0}}, Aabb{{1, 1, 1}, {1, 1, 1}},
                          Aabb{{0, 0, 0}, {4, -1, 4}}, Aabb{{0, 0, 0}, {4, 4, 1e-14}},
                          Aabb{{0, nan, 0}, {4, 4, 4}}, Aabb{{0, 0, 0}, {inf, 4, 4}}}) {
    EXPECT_TRUE(incremental(planes, box).empty());
    EXPECT_TRUE(naive(planes, box).empty());
  }
}

TEST(Slicer, BoxBetweenTwoPlanesGivesNothing) {
  const SlicePlanes planes = SlicePlanes::toward({0, 0, -1}, 0.5);
  const Aabb box{{0, 0, 0.3}, {5, 5, 0.45}};  // depths −0.45 .. −0.3, planes at −0.25, −0.75
  EXPECT_TRUE(incremental(planes, box).empty());
  EXPECT_TRUE(naive(planes, box).empty());
}

TEST(Slicer, ThinBoxesMatchNaive) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> thin(1e-6, 0.6);
  for (int i = 0; i < 500; ++i) {
    const SlicePlanes planes = SlicePlanes::toward(random_direction(rng, i % 3), 0.5);
    Aabb box = random_box(rng);
    box.hi[i % 3] = box.lo[i % 3] + thin(rng);
    const auto inc = incremental(planes, box);
    ASSERT_TRUE(same_polygons(inc, naive(planes, box), 1e-9 * max_extent(box))) << i;
    ASSERT_TRUE(valid_geometry(planes, box, inc)) << i;
  }
}

// Σ area·spacing is a Riemann sum of the cross-section area A(t), which rises then falls (its
// square root is concave, Brunn), so its total variation is 2·max A and the sum is within
// spacing·2·max A of the volume. Every cross-section lies inside the box's projection along dir,
// of area |n_x|·yz + |n_y|·xz + |n_z|·xy: the bound used. Axis views of integer boxes with
// spacing 1/2^j sample A exactly at cell midpoints of a constant: the sum is exact.
TEST(Slicer, AreasTimesSpacingApproximateTheVolume) {
  std::mt19937 rng(5);
  for (int i = 0; i < 300; ++i) {
    const SlicePlanes planes = SlicePlanes::toward(random_direction(rng, i % 3), 0.25);
    const Aabb box = random_box(rng);
    const Vec e{box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]};
    const double volume = e[0] * e[1] * e[2];
    const double projected = std::abs(planes.dir[0]) * e[1] * e[2] +
                             std::abs(planes.dir[1]) * e[0] * e[2] +
                             std::abs(planes.dir[2]) * e[0] * e[1];
    double sum = 0;
    for (const Poly& p : incremental(planes, box)) sum += area(p, planes.dir) * planes.spacing;
    EXPECT_NEAR(sum, volume, 2 * planes.spacing * projected) << i;
  }
  for (double spacing : {1.0, 0.5, 0.25}) {
    const SlicePlanes planes = SlicePlanes::toward({0, -1, 0}, spacing);
    const Aabb box{{-3, -7, 2}, {5, 6, 11}};
    double sum = 0;
    for (const Poly& p : incremental(planes, box)) sum += area(p, planes.dir) * spacing;
    EXPECT_NEAR(sum, 8.0 * 13.0 * 9.0, 1e-9);
  }
}

// A box split 2×2×2 at random points: per plane, the parts' areas add up to the whole box's
// slice area, and where two parts share a face their polygons' vertices on that face coincide.
TEST(Slicer, NeighbouringBoxesMeetExactly) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> frac(0.2, 0.8);
  for (int i = 0; i < 300; ++i) {
    const SlicePlanes planes =
        SlicePlanes::toward(random_direction(rng, i % 3), random_spacing(rng));
    const IncrementalSlicer slicer(planes);
    const Aabb whole = random_box(rng);
    Vec mid;
    for (int a = 0; a < 3; ++a) mid[a] = whole.lo[a] + frac(rng) * (whole.hi[a] - whole.lo[a]);
    const double tol = 1e-9 * max_extent(whole);
    std::array<std::vector<Poly>, 8> parts;
    for (int c = 0; c < 8; ++c) {
      Aabb part;
      for (int a = 0; a < 3; ++a) {
        part.lo[a] = (c >> a) & 1 ? mid[a] : whole.lo[a];
        part.hi[a] = (c >> a) & 1 ? whole.hi[a] : mid[a];
      }
      PolygonSoup s;
      slicer.slice(part, s);
      parts[c] = polygons(s);
    }
    for (const Poly& w : incremental(planes, whole)) {
      double sum = 0;
      std::array<const Poly*, 8> at{};
      for (int c = 0; c < 8; ++c)
        for (const Poly& p : parts[c])
          if (p.plane == w.plane) {
            sum += area(p, planes.dir);
            at[c] = &p;
          }
      ASSERT_NEAR(sum, area(w, planes.dir), tol * max_extent(whole)) << i;
      for (int c = 0; c < 8; ++c)
        for (int a = 0; a < 3; ++a) {
          const int d = c | (1 << a);
          if (d == c || !at[c] || !at[d]) continue;
          auto on_face = [&](const Poly* p) {
            std::vector<Vec> v;
            for (const Vec& x : p->v)
              if (std::abs(x[a] - mid[a]) <= tol) v.push_back(x);
            return v;
          };
          const auto va = on_face(at[c]), vb = on_face(at[d]);
          ASSERT_EQ(va.size(), vb.size()) << i;
          for (const Vec& x : va)
            ASSERT_TRUE(std::any_of(vb.begin(), vb.end(), [&](const Vec& y) {
              return dist(x, y) <= tol;
            })) << i;
        }
    }
  }
}

// ---- API ---------------------------------------------------------------------------------------

TEST(Slicer, AppendsAndReusesMemory) {
  const IncrementalSlicer slicer(SlicePlanes::toward({0.2, -0.4, 0.9}, 0.5));
  const Aabb a{{0, 0, 0}, {10, 10, 10}}, b{{10, 0, 0}, {20, 10, 10}};
  PolygonSoup one, two, both;
  slicer.slice(a, one);
  slicer.slice(b, two);
  slicer.slice(a, both);
  slicer.slice(b, both);
  EXPECT_EQ(both.size(), one.size() + two.size());
  std::vector<double> xyz = one.xyz;
  xyz.insert(xyz.end(), two.xyz.begin(), two.xyz.end());
  EXPECT_EQ(both.xyz, xyz);
  const std::size_t capacity = both.xyz.capacity();
  const double* data = both.xyz.data();
  both.clear();
  slicer.slice(a, both);
  EXPECT_EQ(both.xyz, one.xyz);
  EXPECT_EQ(both.xyz.capacity(), capacity);
  EXPECT_EQ(both.xyz.data(), data);
}

TEST(Slicer, RejectsInvalidPlanes) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(SlicePlanes::toward({0, 0, 0}, 0.5), UsageError);
  EXPECT_THROW(SlicePlanes::toward({nan, 0, 1}, 0.5), UsageError);
  EXPECT_THROW(SlicePlanes::toward({0, 0, 1}, 0), UsageError);
  EXPECT_THROW(SlicePlanes::toward({0, 0, 1}, -1), UsageError);
  EXPECT_THROW(SlicePlanes::toward({0, 0, 1}, nan), UsageError);
  EXPECT_THROW(IncrementalSlicer(SlicePlanes{{0, 0, 2}, 0.5}), UsageError);
  PolygonSoup s;
  EXPECT_THROW(naive_slice(SlicePlanes{{1, 1, 0}, 0.5}, Aabb{{0, 0, 0}, {1, 1, 1}}, s), UsageError);
  const IncrementalSlicer tiny(SlicePlanes{{0, 0, 1}, 1e-9});
  EXPECT_THROW(tiny.slice(Aabb{{0, 0, 0}, {1, 1, 1}}, s), UsageError);
  try {
    SlicePlanes::toward({0, 0, 1}, -1);
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("spacing"), std::string::npos);
  }
}

TEST(Slicer, TowardNormalizes) {
  const SlicePlanes p = SlicePlanes::toward({0, 3, -4}, 0.75);
  EXPECT_DOUBLE_EQ(p.dir[1], 0.6);
  EXPECT_DOUBLE_EQ(p.dir[2], -0.8);
  EXPECT_EQ(p.spacing, 0.75);
  EXPECT_DOUBLE_EQ(p.depth(2), 1.875);
}

TEST(Slicer, GeometricBoxClipsTheLastSampleLayer) {
  const Dims d{33, 20, 5};
  EXPECT_EQ(geometric_box(Box{{0, 0, 0}, {31, 20, 5}}, d), (Aabb{{0, 0, 0}, {31, 19, 4}}));
  EXPECT_EQ(geometric_box(Box{{31, 10, 2}, {33, 20, 3}}, d), (Aabb{{31, 10, 2}, {32, 19, 3}}));
}

}  // namespace
}  // namespace tsp

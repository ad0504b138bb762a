// Leven's adaptive octree (issue 31 item 1): the subdivision against fields whose homogeneous
// regions are known, the stored bricks against the uniform build of the same mesh (same
// voxelizer, same lattice points), the bricks below a stop against the trilinear reconstruction
// of the stopped node, the statistics against the uniform build's, and the traversal never
// below a stop.
#include "tsp/adaptive/adaptive_build.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "support/mesh_shapes.h"
#include "support/paths.h"
#include "tsp/build/build.h"
#include "tsp/core/error.h"
#include "tsp/store/tsp_file.h"
#include "tsp/tree/traversal.h"
#include "tsp/voxelize/voxelized_source.h"

namespace tsp {
namespace {

// Meshes held in memory, one per step.
class MemoryMeshSource final : public MeshSource {
 public:
  explicit MemoryMeshSource(std::vector<Mesh> steps) : steps_(std::move(steps)) {}
  int steps() const override { return int(steps_.size()); }
  std::string describe() const override { return "memory mesh"; }
  std::vector<std::string> files() const override { return {}; }
  std::vector<double> times() const override { return {}; }
  Mesh read_step(int t) override { return steps_[std::size_t(t)]; }

 private:
  std::vector<Mesh> steps_;
};

// The field the tests use: 0 for x < kFlatBelow, then growing with x and y (t scales it).
constexpr double kFlatBelow = 0.75;
double field(double x, double y, int t) {
  return x < kFlatBelow ? 0.0 : (x - kFlatBelow) * (1.0 + y) * (1.0 + t);
}

// An n³ box of hexahedra over [0, 1]³ carrying field() at step t.
Mesh unit_box(int n, int t) {
  Mesh m = tsptest::hex_box(n, 3);
  for (double& p : m.points) p /= n;
  for (std::int64_t p = 0; p < m.point_count(); ++p)
    m.values[std::size_t(p)] = float(field(m.points[std::size_t(3 * p)], m.points[std::size_t(3 * p + 1)], t));
  return m;
}

std::vector<Mesh> series(int n, int steps) {
  std::vector<Mesh> s;
  for (int t = 0; t < steps; ++t) s.push_back(unit_box(n, t));
  return s;
}

constexpr int kResolution = 29;  // 28 cells: 4 bricks of 8 per axis, depth 2
constexpr int kBrick = 8;

AdaptiveOptions options(double error) {
  AdaptiveOptions o;
  o.error = error;
  o.voxelize.resolution = kResolution;
  o.build.brick_size = kBrick;
  o.build.range = ValueRange{0, 1.25 * 2 * 2};  // covers field() at t ≤ 1, the same in both builds
  o.build.threads = 2;
  return o;
}

std::string adaptive(const std::vector<Mesh>& steps, double error, AdaptiveReport* report = nullptr) {
  const std::string path = (tsptest::temp_dir() / "adaptive.tsp").string();
  MemoryMeshSource src(steps);
  const AdaptiveReport r = build_adaptive_tsp(src, path, options(error));
  if (report) *report = r;
  return path;
}

std::string uniform(const std::vector<Mesh>& steps) {
  const std::string path = (tsptest::temp_dir() / "uniform.tsp").string();
  const AdaptiveOptions a = options(0);
  auto src = voxelized_source(std::make_unique<MemoryMeshSource>(steps), a.voxelize);
  build_tsp_file(*src, path, a.build);
  return path;
}

// Cells (1/32) smaller than every node's voxels (≥ 1/28): only the field decides. The root's
// children below x = ½ see a flat field (their regions end before kFlatBelow) and stop; the
// others split down to the leaves.
TEST(AdaptiveBuild, StopsWhereTheFieldIsFlatAndSplitsWhereItIsNot) {
  AdaptiveReport rep;
  auto file = TspFile::open(adaptive(series(32, 2), 1e-6, &rep));
  const Octree& o = file->tree().octree();
  EXPECT_EQ(o.depth(), 2);
  EXPECT_TRUE(o.has_stops());
  EXPECT_FALSE(o.stopped(0));
  int stopped = 0;
  for (int oct = 0; oct < 8; ++oct) {
    const int c = o.split_children(0)[std::size_t(oct)];
    ASSERT_GE(c, 0);
    const bool lower_x = (oct & 1) == 0;
    EXPECT_EQ(o.stopped(c), lower_x) << "child " << oct;
    stopped += o.stopped(c);
    if (lower_x) {
      EXPECT_TRUE(o.node(c).is_leaf());
      EXPECT_EQ(o.node(c).brick, o.node_brick(c));
      EXPECT_GE(o.node(c).brick, o.brick_count());  // its level brick
      for (int g : o.split_children(c)) {
        if (g < 0) continue;
        EXPECT_FALSE(o.reachable(g));
        EXPECT_FALSE(o.brick_present(o.node_brick(g)));
      }
    } else {
      for (int g : o.node(c).children) {
        if (g >= 0) {
          EXPECT_TRUE(o.node(g).is_leaf() && !o.stopped(g));
        }
      }
    }
  }
  EXPECT_EQ(stopped, 4);
  EXPECT_EQ(rep.stopped, 4);
  EXPECT_EQ(rep.nodes, 1 + 8 + 4 * 8);
  EXPECT_LT(rep.brick_bytes, rep.complete_brick_bytes);
}

// With E above the whole field's spread the root stops: one level brick holds the data.
TEST(AdaptiveBuild, AThresholdAboveTheSpreadStopsAtTheRoot) {
  AdaptiveReport rep;
  auto file = TspFile::open(adaptive(series(32, 1), 10.0, &rep));
  EXPECT_TRUE(file->tree().octree().stopped(0));
  EXPECT_TRUE(file->tree().octree().node(0).is_leaf());
  EXPECT_EQ(rep.nodes, 1);
}

// Cells (¼) larger than the root's voxels (4/28): no cell is finer than any node's voxels, so
// even E = 0 stops at the root (Leven's first condition).
TEST(AdaptiveBuild, CellsLargerThanTheVoxelsStopAtTheRoot) {
  auto file = TspFile::open(adaptive(series(4, 1), 0.0));
  EXPECT_TRUE(file->tree().octree().stopped(0));
}

// Every present leaf brick holds the uniform build's samples (the same voxelizer at the same
// points); every absent one reads as the trilinear reconstruction of its stopped node, which for
// the flat region is exact.
TEST(AdaptiveBuild, PresentBricksMatchTheUniformBuildAndAbsentOnesReadFromTheirStop) {
  const std::vector<Mesh> s = series(32, 2);
  auto a = TspFile::open(adaptive(s, 1e-6));
  auto u = TspFile::open(uniform(s));
  const Octree& o = a->tree().octree();
  ASSERT_EQ(o.dims(), u->tree().octree().dims());
  int present = 0, absent = 0;
  for (int b = 0; b < o.brick_count(); ++b)
    for (int t = 0; t < 2; ++t) {
      std::vector<std::uint16_t> ca(std::size_t(o.lattice(b).count())), cu(ca.size());
      a->read_brick(b, t, ca);
      u->read_brick(b, t, cu);
      (o.brick_present(b) ? present : absent)++;
      for (std::size_t i = 0; i < ca.size(); ++i)
        ASSERT_NEAR(int(ca[i]), int(cu[i]), 1) << "brick " << b << " step " << t << " sample " << i;
    }
  EXPECT_GT(present, 0);
  EXPECT_GT(absent, 0);
}

// An inner node's level brick is made from its children's samples, not its cells: for a
// trilinear field (reproduced exactly by the hexahedra and by the children's trilinear
// reconstruction) every inner node's samples are the field at their lattice points.
TEST(AdaptiveBuild, InnerLevelBricksAreTheFieldAtTheirSamples) {
  auto g = [](double x, double y, double z, int t) { return 0.5 + x + 2 * y * z + 0.25 * t; };
  std::vector<Mesh> steps;
  for (int t = 0; t < 2; ++t) {
    Mesh m = tsptest::hex_box(32, 3);
    for (double& p : m.points) p /= 32;
    for (std::int64_t p = 0; p < m.point_count(); ++p) {
      const double* q = m.points.data() + 3 * p;
      m.values[std::size_t(p)] = float(g(q[0], q[1], q[2], t));
    }
    steps.push_back(m);
  }
  auto file = TspFile::open(adaptive(steps, 1e-9));
  const Octree& o = file->tree().octree();
  const TspMetadata& md = file->metadata();
  const Quantizer q{file->tree().value_range()};
  int inner = 0;
  for (int id = 0; id < o.size(); ++id) {
    if (!o.reachable(id) || o.node(id).is_leaf()) continue;
    ++inner;
    const int b = o.node_brick(id);
    const BrickLattice l = o.lattice(b);
    ASSERT_GT(l.factor[0], 1) << "node " << id;
    for (int t = 0; t < 2; ++t) {
      std::vector<std::uint16_t> codes(std::size_t(l.count()));
      file->read_brick(b, t, codes);
      std::size_t i = 0;
      for (int z = 0; z < l.samples[2]; ++z)
        for (int y = 0; y < l.samples[1]; ++y)
          for (int x = 0; x < l.samples[0]; ++x, ++i) {
            const int v[3] = {std::min(l.origin[0] + x * l.factor[0], o.dims()[0] - 1),
                              std::min(l.origin[1] + y * l.factor[1], o.dims()[1] - 1),
                              std::min(l.origin[2] + z * l.factor[2], o.dims()[2] - 1)};
            const double want = g(md.origin[0] + v[0] * md.spacing[0], md.origin[1] + v[1] * md.spacing[1],
                                  md.origin[2] + v[2] * md.spacing[2], t);
            ASSERT_NEAR(int(codes[i]), int(q.encode(float(want))), 1)
                << "node " << id << " step " << t << " sample " << x << "," << y << "," << z;
          }
    }
  }
  EXPECT_EQ(inner, 1 + 8);  // no stops at E ≈ 0: the root and its children
}

// The statistics of the whole volume (the root) agree with the uniform build's: a stopped
// node's samples weigh for the voxels they stand for.
TEST(AdaptiveBuild, StatisticsAgreeWithTheUniformBuild) {
  const std::vector<Mesh> s = series(32, 2);
  auto a = TspFile::open(adaptive(s, 1e-6));
  auto u = TspFile::open(uniform(s));
  const TspTree& ta = a->tree();
  const TspTree& tu = u->tree();
  for (int tau = 0; tau < ta.time().size(); ++tau) {
    const NodeStats& sa = ta.stats(ta.id(0, tau));
    const NodeStats& su = tu.stats(tu.id(0, tau));
    EXPECT_NEAR(sa.mean, su.mean, 0.02 * su.mean) << tau;
    EXPECT_NEAR(sa.std, su.std, 0.05 * su.std) << tau;
    EXPECT_NEAR(sa.min, su.min, 1e-3);
    EXPECT_NEAR(sa.max, su.max, 1e-3);
  }
  EXPECT_NEAR(ta.inside_fraction(0), tu.inside_fraction(0), 1e-3);
}

// At zero tolerance the traversal emits nodes that tile the grid's leaf bricks once each and
// never a node below a stop; the stopped nodes are among them, drawn from their level bricks.
TEST(AdaptiveBuild, TheTraversalTreatsAStoppedNodeAsALeaf) {
  auto file = TspFile::open(adaptive(series(32, 2), 1e-6));
  const TspTree& tree = file->tree();
  const Octree& o = tree.octree();
  const NodeErrors errors = scalar_errors(tree);
  const TraversalQuery q{.tree = tree, .step = 1, .tol = {0, 0}, .errors = errors,
                         .view = ViewOrder::orthographic({0.3, 0.5, 0.8})};
  std::vector<int> covered(std::size_t(o.brick_count()), 0);
  int stops = 0;
  for (const Emitted& e : traverse(q)) {
    ASSERT_TRUE(o.reachable(e.octree_id));
    EXPECT_TRUE(o.node(e.octree_id).is_leaf());  // zero tolerance: leaves and stops only
    stops += o.stopped(e.octree_id);
    o.for_each_brick(e.octree_id, [&](int b) { covered[std::size_t(b)]++; });
  }
  EXPECT_EQ(stops, 4);
  for (int c : covered) EXPECT_EQ(c, 1);
}

// A remeshed series (another cell count at step 1) gets a cell list per step.
TEST(AdaptiveBuild, ARemeshedSeriesBuildsWithListsPerStep) {
  std::vector<Mesh> s{unit_box(32, 0), unit_box(16, 1)};
  AdaptiveReport rep;
  auto file = TspFile::open(adaptive(s, 1e-6, &rep));
  EXPECT_EQ(file->tree().time().steps(), 2);
  EXPECT_EQ(rep.stopped, 4);
  // The uniform build of the same series agrees on the finer step's present leaves.
  auto u = TspFile::open(uniform(s));
  const Octree& o = file->tree().octree();
  for (int b = 0; b < o.brick_count(); ++b) {
    if (!o.brick_present(b)) continue;
    std::vector<std::uint16_t> ca(std::size_t(o.lattice(b).count())), cu(ca.size());
    file->read_brick(b, 1, ca);
    u->read_brick(b, 1, cu);
    for (std::size_t i = 0; i < ca.size(); ++i) ASSERT_NEAR(int(ca[i]), int(cu[i]), 1);
  }
}

TEST(AdaptiveBuild, RefusesABadThreshold) {
  MemoryMeshSource src(series(4, 1));
  AdaptiveOptions o = options(-1);
  EXPECT_THROW(build_adaptive_tsp(src, (tsptest::temp_dir() / "x.tsp").string(), o), UsageError);
  o.error = std::nan("");
  EXPECT_THROW(build_adaptive_tsp(src, (tsptest::temp_dir() / "x.tsp").string(), o), UsageError);
  EXPECT_FALSE(std::filesystem::exists(tsptest::temp_dir() / "x.tsp"));
}

}  // namespace
}  // namespace tsp

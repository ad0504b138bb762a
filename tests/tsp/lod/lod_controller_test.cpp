// The LOD controller on a simulated renderer whose true frame time differs from the controller's
// cost estimate per node: it holds a target, refines fully without one, keeps transparent data
// coarse, respects the texture budget and falls back to a smaller render target.
#include "tsp/lod/lod_controller.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace tsp {
namespace {

// A tree whose every node spans values [0, 1] with a level residual growing with the level.
TspTree make_tree(Dims d, int brick) {
  TspTree tree(d, 2, brick);
  for (int i = 0; i < tree.size(); ++i) {
    tree.stats(i).min = 0;
    tree.stats(i).max = 1;
    tree.stats(i).mean = 0.5;
  }
  const Octree& o = tree.octree();
  auto errors = tree.level_errors();
  for (int j = 0; j < o.level_brick_count(); ++j)
    for (int t = 0; t < 2; ++t)
      errors[std::size_t(j) * 2 + t] =
          0.01f * float(1 << o.lod_level(o.stored_brick_node(o.brick_count() + j)));
  return tree;
}

TransferFunction ramp_tf(float alpha) {
  std::vector<TfPoint> pts = {{0.0, {0.f, 0.f, 1.f, 0.f}}, {1.0, {1.f, 0.5f, 0.f, alpha}}};
  return TransferFunction::from_points({0, 1}, pts);
}

Camera camera(Dims d, double azimuth, double elevation = 20) {
  CameraParams p;
  p.width = 640;
  p.height = 480;
  p.azimuth_deg = azimuth;
  p.elevation_deg = elevation;
  return Camera(d, p);
}

// The "renderer": 4 ms fixed plus the controller's node costs, each off by a fixed random factor
// in [0.6, 1.4], plus 5 % noise per frame.
struct SimulatedRenderer {
  std::vector<double> skew;
  std::mt19937 rng{7};
  double ms_per_cost = 0;
  SimulatedRenderer(const Octree& o, double per_cost)
      : skew(std::size_t(o.size())), ms_per_cost(per_cost) {
    std::uniform_real_distribution<double> u(0.6, 1.4);
    for (double& s : skew) s = u(rng);
  }
  double frame(const LodController& c) {
    double cost = 0;
    for (int id : c.cut().nodes()) cost += c.node_cost(id) * skew[std::size_t(id)];
    std::normal_distribution<double> noise(1, 0.05);
    const double scale = c.render_scale();
    return (4 + ms_per_cost * cost) * scale * scale * noise(rng);
  }
};

TEST(LodController, HoldsTheTargetOnASimulatedRenderer) {
  const Dims d{257, 257, 257};
  const TspTree tree = make_tree(d, 32);
  const TransferFunction tf = ramp_tf(0.005f);  // thin: every node stays visible
  // Targets past the first splits (each of which doubles the root's samples), where the cut can
  // move by small steps; full resolution takes about 150 ms.
  for (double target : {60.0, 90.0, 120.0}) {
    LodOptions opt;
    opt.target_ms = target;
    LodController c(tree, opt);
    LodController full(tree, LodOptions{});
    for (int k = 0; k < 200 && full.update(camera(d, 30), 0, tf, 0.5).splits > 0; ++k) {
    }
    double full_cost = 0;
    for (int id : full.cut().nodes()) full_cost += full.node_cost(id);
    SimulatedRenderer r(tree.octree(), 150.0 / full_cost);
    std::vector<double> times;
    for (int frame = 0; frame < 120; ++frame) {
      c.update(camera(d, 30 + 2 * frame), 0, tf, 0.5);
      const double ms = r.frame(c);
      c.measured(ms);
      if (frame >= 40) times.push_back(ms);
    }
    std::sort(times.begin(), times.end());
    const double median = times[times.size() / 2];
    const double p90 = times[times.size() * 9 / 10];
    EXPECT_NEAR(median, target, 0.2 * target) << "target " << target;
    EXPECT_LT(p90, 1.5 * target) << "target " << target;
    EXPECT_TRUE(c.cut().covers_once());
  }
}

// The 129³ volume of 16³ bricks most tests drive, seen through a ramp of opacity 0.05.
struct Cube {
  Dims d{129, 129, 129};
  TspTree tree = make_tree(d, 16);
  TransferFunction tf = ramp_tf(0.05f);

  /// One frame of c seen from azimuth 30° through tf.
  LodFrameStats update(LodController& c) const { return c.update(camera(d, 30), 0, tf, 0.5); }

  /// `frames` frames of c (update), each then measured as taking ms(its stats) milliseconds.
  template <typename F>
  void drive(LodController& c, int frames, F&& ms) const {
    for (int k = 0; k < frames; ++k) c.measured(ms(update(c)));
  }
};

TEST(LodController, WithoutATargetRefinesUntilNoErrorIsLeft) {
  const Cube cube;
  const Octree& o = cube.tree.octree();
  LodOptions opt;
  opt.min_error = 0;
  LodController c(cube.tree, opt);
  int frames = 0;
  LodFrameStats st;
  do {
    st = cube.update(c);
    ++frames;
  } while (st.splits > 0 && frames < 1000);
  EXPECT_EQ(c.cut().size(), o.brick_count());  // every node split: full resolution
  EXPECT_EQ(st.nodes_per_level[0], o.brick_count());
  // split_limit per frame bounds how fast it gets there.
  EXPECT_GE(frames, (o.size() - o.brick_count()) / opt.split_limit);
}

TEST(LodController, TransparentDataStaysCoarseForFree) {
  Cube cube;
  cube.tf = ramp_tf(0.f);  // α = 0 everywhere
  LodOptions opt;
  opt.min_error = 0;
  LodController c(cube.tree, opt);
  for (int k = 0; k < 20; ++k) cube.update(c);
  EXPECT_EQ(c.cut().size(), 1);
}

TEST(LodController, NodesHiddenBehindOpaqueMatterStayCoarse) {
  const Dims d{129, 129, 129};
  const TspTree tree = make_tree(d, 16);
  LodOptions opt;
  opt.min_error = 1e-3;
  LodController c(tree, opt);
  for (int k = 0; k < 500 && c.update(camera(d, 0, 0), 0, ramp_tf(0.5f), 0.5).splits > 0; ++k) {
  }
  // Looking level along +y into nearly opaque data: the front half is refined, the back not.
  int front = 0, back = 0;
  for (int id : c.cut().nodes()) {
    if (tree.octree().lod_level(id) > 0) continue;
    (tree.octree().node(id).box.lo[1] < 64 ? front : back)++;
  }
  EXPECT_GT(front, 100);
  EXPECT_LT(back, front / 4);
}

TEST(LodController, LikelySplitsAreChildrenOfTheWorstCutNodes) {
  const Cube cube;
  LodOptions opt;
  opt.split_limit = 2;
  LodController c(cube.tree, opt);
  for (int k = 0; k < 3; ++k) cube.update(c);
  const std::vector<int> bricks = c.likely_split_bricks(3);
  ASSERT_FALSE(bricks.empty());
  const Octree& o = cube.tree.octree();
  for (int b : bricks) {
    const int parent = o.node(o.stored_brick_node(b)).parent;
    EXPECT_TRUE(c.cut().contains(parent)) << "brick " << b;
    EXPECT_TRUE(c.cut().can_split(parent));
  }
}

TEST(LodController, RespectsTheTextureBudget) {
  const Cube cube;
  LodOptions opt;
  opt.min_error = 0;
  const std::int64_t brick = 16 * 16 * 16 * 2;
  opt.texture_budget = 100 * brick;
  LodController c(cube.tree, opt);
  LodFrameStats st;
  for (int k = 0; k < 100; ++k) st = cube.update(c);
  EXPECT_LE(st.texture_bytes, opt.texture_budget);
  EXPECT_GT(c.cut().size(), 50);  // it got as close as whole splits allow
  EXPECT_TRUE(c.cut().covers_once());
}

TEST(LodController, ShrinksTheRenderTargetWhenEvenTheRootIsTooSlow) {
  const Cube cube;
  LodOptions opt;
  opt.target_ms = 10;
  LodController c(cube.tree, opt);
  // The root alone takes 40 ms at full size.
  const auto root_ms = [&](const LodFrameStats&) {
    return 40 * c.render_scale() * c.render_scale();
  };
  double ms = 0;
  cube.drive(c, 30, [&](const LodFrameStats& st) { return ms = root_ms(st); });
  EXPECT_EQ(c.cut().size(), 1);
  EXPECT_LT(c.render_scale(), 0.7);
  EXPECT_NEAR(ms, 10, 3);
  // Once there is time again, the scale returns to 1 before anything is split.
  c.set_target(200);
  cube.drive(c, 30, root_ms);
  EXPECT_EQ(c.render_scale(), 1.0);
}

TEST(LodController, FallsBackToSplatsWhenEvenTheRootIsTooSlow) {
  const Cube cube;
  LodOptions opt;
  opt.target_ms = 10;
  opt.fallback = LodFallback::splats;
  LodController c(cube.tree, opt);
  // The textured root takes 40 ms; a splat frame 2 ms plus 0.5 ms per splat.
  std::vector<double> times;
  int most_splats = 0;
  cube.drive(c, 40, [&](const LodFrameStats& st) {
    EXPECT_EQ(st.render_scale, 1.0);  // splats instead of a smaller target
    EXPECT_EQ(c.cut().size(), 1);
    const double ms = c.splatting() ? 2 + 0.5 * st.splats : 40.0;
    if (c.splatting()) {
      EXPECT_EQ(st.splats, [&] {
        int n = 0;
        for (LodStop s : c.stops()) n += s == LodStop::splat;
        return n;
      }());
      most_splats = std::max(most_splats, st.splats);
    }
    times.push_back(ms);
    return ms;
  });
  EXPECT_TRUE(c.splatting());
  EXPECT_GT(most_splats, 1);  // refined past the root's single splat while it fitted
  for (std::size_t k = 10; k < times.size(); ++k) EXPECT_LE(times[k], 10 * 1.1) << "frame " << k;
  // Once the coarsest textured cut fits again, the frames are textured and the cut refines.
  c.set_target(200);
  cube.drive(c, 10,
             [&](const LodFrameStats&) { return c.splatting() ? 5 : 40.0 + 0.5 * c.cut().size(); });
  EXPECT_FALSE(c.splatting());
  EXPECT_GT(c.cut().size(), 1);
  for (LodStop s : c.stops()) EXPECT_NE(s, LodStop::splat);
}

}  // namespace
}  // namespace tsp

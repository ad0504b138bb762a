#include "tsp/tree/traversal.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace tsp {
namespace {

constexpr float kHuge = 1e30f;

NodeErrors filled(const TspTree& tree, float spatial, float temporal) {
  NodeErrors e;
  e.spatial.assign(tree.size(), spatial);
  e.temporal.assign(tree.size(), temporal);
  return e;
}

// Uniform random errors in [0, 1) times kGrowth per level above the deepest octree and time
// levels, so that with tolerances around 0.5 the emitted nodes mix several octree levels
// (plain uniform errors mostly stop at the root or go to the leaves).
constexpr float kGrowth = 1.2f;
NodeErrors random_errors(const TspTree& tree, std::mt19937& rng, bool graded) {
  std::uniform_real_distribution<float> u(0.f, 1.f);
  NodeErrors e = filled(tree, 0, 0);
  for (int i = 0; i < tree.size(); ++i) {
    const int above = tree.octree().depth() - tree.octree().node(tree.octree_of(i)).level +
                      tree.time().depth() - tree.time().level(tree.time_of(i));
    const float scale = graded ? std::pow(kGrowth, float(above)) : 1.f;
    e.spatial[i] = u(rng) * scale;
    e.temporal[i] = u(rng) * scale;
  }
  return e;
}

// Number of distinct octree levels among the emitted nodes.
int levels_of(const TspTree& tree, const std::vector<Emitted>& out) {
  std::set<int> levels;
  for (const Emitted& e : out) levels.insert(tree.octree().node(e.octree_id).level);
  return int(levels.size());
}

const ViewOrder kAnyView = ViewOrder::orthographic({1, 1, 1});

// ---- independent checks -------------------------------------------------------------

// Every voxel of the grid lies in exactly one emitted node's box.
void expect_tiles_once(const TspTree& tree, const std::vector<Emitted>& out,
                       const std::string& ctx) {
  const Dims d = tree.octree().dims();
  std::vector<unsigned char> hits(d.count(), 0);
  for (const Emitted& e : out) {
    ASSERT_GE(e.octree_id, 0) << ctx;
    ASSERT_LT(e.octree_id, tree.octree().size()) << ctx;
    const Box b = tree.octree().node(e.octree_id).box;
    for (int z = b.lo[2]; z < b.hi[2]; ++z)
      for (int y = b.lo[1]; y < b.hi[1]; ++y)
        for (int x = b.lo[0]; x < b.hi[0]; ++x) ++hits[x + d.x * (y + std::int64_t(d.y) * z)];
  }
  const auto bad = std::count_if(hits.begin(), hits.end(), [](unsigned char c) { return c != 1; });
  EXPECT_EQ(bad, 0) << ctx << ": voxels not covered exactly once";
}

// Time nodes on the path from the root to leaf_of(t), root first, found by walking parents.
std::vector<int> time_path(const TimeTree& time, int t) {
  std::vector<int> path;
  for (int tau = time.leaf_of(t); tau >= 0; tau = time.parent(tau)) path.push_back(tau);
  std::reverse(path.begin(), path.end());
  return path;
}

// The rule of spec §5 stated per node rather than as a walk: (o, τ) is emitted iff no octree
// ancestor of o had a coherent time node on t's path, and τ is the first coherent one on o's
// path (or o is a leaf without any, and τ is the leaf [t, t]).
void expect_follows_rule(const TspTree& tree, int t, const Tolerances& tol, const NodeErrors& e,
                         const std::vector<Emitted>& out, const std::string& ctx) {
  const std::vector<int> path = time_path(tree.time(), t);
  auto first_coherent = [&](int o) {
    const bool leaf = tree.octree().node(o).is_leaf();
    for (int tau : path) {
      const int id = tree.id(o, tau);
      if (e.temporal[id] <= tol.temporal && (leaf || e.spatial[id] <= tol.spatial)) return tau;
    }
    return -1;
  };
  for (const Emitted& em : out) {
    EXPECT_TRUE(em.span.contains(t)) << ctx;
    EXPECT_EQ(em.span, tree.time().span(em.time_id)) << ctx;
    const int want = first_coherent(em.octree_id);
    if (want >= 0) {
      EXPECT_EQ(em.time_id, want) << ctx << " node " << em.octree_id;
    } else {
      EXPECT_TRUE(tree.octree().node(em.octree_id).is_leaf()) << ctx;
      EXPECT_EQ(em.time_id, tree.time().leaf_of(t)) << ctx;
    }
    for (int p = tree.octree().node(em.octree_id).parent; p >= 0; p = tree.octree().node(p).parent)
      EXPECT_EQ(first_coherent(p), -1) << ctx << " ancestor " << p << " was coherent";
  }
}

// Back-to-front check. For every pair (A drawn before B) of boxes separated along exactly one
// axis a whose projections on the other two axes overlap with positive area, B must not lie
// strictly behind A across a plane between them: orthographic, B is behind when it is on the
// side dir[a] points to; perspective, when the eye is strictly on A's side of A's facing
// face. Pairs the eye sits between, or with dir[a] = 0, allow either order.
struct Viewer {
  bool perspective;
  std::array<double, 3> v;
};

bool behind(const Box& a, const Box& b, int axis, const Viewer& view) {
  const bool b_upper = a.hi[axis] <= b.lo[axis];
  if (view.perspective) return b_upper ? view.v[axis] < a.hi[axis] : view.v[axis] > a.lo[axis];
  return b_upper ? view.v[axis] > 0 : view.v[axis] < 0;
}

// Empty when the order is back-to-front, otherwise the first violation found.
std::string order_violation(const std::vector<Box>& boxes, const Viewer& view) {
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      const Box &a = boxes[i], &b = boxes[j];
      int separated = -1, overlapping = 0;
      for (int ax = 0; ax < 3; ++ax) {
        const int lo = std::max(a.lo[ax], b.lo[ax]), hi = std::min(a.hi[ax], b.hi[ax]);
        if (hi > lo) {
          ++overlapping;
        } else {
          separated = ax;
        }
      }
      if (overlapping != 2) continue;
      if (behind(a, b, separated, view))
        return "box #" + std::to_string(j) + " drawn after box #" + std::to_string(i) +
               " lies behind it along axis " + std::to_string(separated);
    }
  }
  return {};
}

std::vector<Box> boxes_of(const TspTree& tree, const std::vector<Emitted>& out) {
  std::vector<Box> boxes;
  for (const Emitted& e : out) boxes.push_back(tree.octree().node(e.octree_id).box);
  return boxes;
}

struct Grid {
  Dims dims;
  int brick;
  int steps;
};
const Grid kGrids[] = {{{64, 64, 64}, 8, 5}, {{37, 20, 5}, 4, 7}, {{48, 48, 14}, 16, 4}};

std::string name(const Grid& g) {
  return to_string(g.dims) + " B=" + std::to_string(g.brick);
}

// ---- scalar_errors ------------------------------------------------------------------

TEST(ScalarErrors, CopiesSpatialAndTemporalErrorsPerNode) {
  TspTree tree({20, 20, 20}, 3, 8);
  for (int i = 0; i < tree.size(); ++i) {
    tree.stats(i).spatial_error = 0.5f * i;
    tree.stats(i).temporal_error = 1000.f - i;
  }
  NodeErrors e = scalar_errors(tree);
  ASSERT_EQ(int(e.spatial.size()), tree.size());
  ASSERT_EQ(int(e.temporal.size()), tree.size());
  for (int i = 0; i < tree.size(); ++i) {
    EXPECT_EQ(e.spatial[i], 0.5f * i);
    EXPECT_EQ(e.temporal[i], 1000.f - i);
  }
}

// ---- traversal results ----------------------------------------------------------------

TEST(Traverse, AllCoherentEmitsOnlyTheRootOverAllSteps) {
  for (const Grid& g : kGrids) {
    TspTree tree(g.dims, g.steps, g.brick);
    NodeErrors e = filled(tree, 0, 0);
    for (int t = 0; t < g.steps; ++t) {
      auto out = traverse({.tree = tree, .step = t, .tol = {0, 0}, .errors = e, .view = kAnyView});
      ASSERT_EQ(out.size(), 1u) << name(g);
      EXPECT_EQ(out[0], (Emitted{0, 0, Span{0, g.steps - 1}})) << name(g);
    }
  }
}

TEST(Traverse, NothingCoherentEmitsEveryLeafBrickAtItsStep) {
  for (const Grid& g : kGrids) {
    TspTree tree(g.dims, g.steps, g.brick);
    NodeErrors e = filled(tree, kHuge, kHuge);
    for (int t = 0; t < g.steps; ++t) {
      auto out =
          traverse({.tree = tree, .step = t, .tol = {0.5, 0.5}, .errors = e, .view = kAnyView});
      ASSERT_EQ(int(out.size()), tree.octree().brick_count()) << name(g);
      std::set<int> bricks;
      for (const Emitted& em : out) {
        ASSERT_TRUE(tree.octree().node(em.octree_id).is_leaf());
        bricks.insert(tree.octree().node(em.octree_id).brick);
        EXPECT_EQ(em.span, (Span{t, t}));
        EXPECT_EQ(em.time_id, tree.time().leaf_of(t));
      }
      EXPECT_EQ(int(bricks.size()), tree.octree().brick_count());
    }
  }
}

TEST(Traverse, TemporalOnlyCoherenceGivesLeavesWithLargestCoherentSpans) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (const Grid& g : kGrids) {
    TspTree tree(g.dims, g.steps, g.brick);
    NodeErrors e = filled(tree, kHuge, 0);
    for (float& v : e.temporal) v = u(rng);
    const Tolerances tol{0.5, 0.6};
    for (int t = 0; t < g.steps; ++t) {
      auto out = traverse({.tree = tree, .step = t, .tol = tol, .errors = e, .view = kAnyView});
      ASSERT_EQ(int(out.size()), tree.octree().brick_count()) << name(g);
      for (const Emitted& em : out) {
        ASSERT_TRUE(tree.octree().node(em.octree_id).is_leaf());
        // Walk up from [t, t]; the last (highest) node with e_t ≤ tol wins, else the leaf.
        int want = tree.time().leaf_of(t);
        for (int tau = want; tau >= 0; tau = tree.time().parent(tau))
          if (e.temporal[tree.id(em.octree_id, tau)] <= tol.temporal) want = tau;
        EXPECT_EQ(em.time_id, want) << name(g) << " t=" << t;
        EXPECT_EQ(em.span, tree.time().span(want));
      }
    }
  }
}

// A 7×7×4 grid with B = 4 has 2×2×1 bricks: the root splits x and y into four leaves.
// Time tree over 4 steps: 0 [0,3], 1 [0,1], 2 [2,3], 3 [0,0], 4 [1,1], 5 [2,2], 6 [3,3].
TEST(Traverse, MixedCaseWorkedOutByHand) {
  TspTree tree({7, 7, 4}, 4, 4);
  const Octree& oct = tree.octree();
  ASSERT_EQ(oct.size(), 5);
  for (int k = 0; k < 4; ++k) ASSERT_EQ(oct.node(0).children[k], 1 + k);
  for (int k = 4; k < 8; ++k) ASSERT_EQ(oct.node(0).children[k], -1);
  ASSERT_EQ(tree.time().span(2), (Span{2, 3}));
  ASSERT_EQ(tree.time().span(5), (Span{2, 2}));

  NodeErrors e = filled(tree, kHuge, kHuge);
  auto set = [&](int o, int tau, float es, float et) {
    e.spatial[tree.id(o, tau)] = es;
    e.temporal[tree.id(o, tau)] = et;
  };
  const Tolerances tol{0.1, 0.1};
  // Root: temporally coherent over [0,3] but not spatially; [0,1] fully coherent; [2,3]
  // and its leaves fail (spatially), so steps 2 and 3 descend into the leaves.
  set(0, 0, 0.5f, 0.05f);
  set(0, 1, 0.05f, 0.05f);
  set(0, 5, 0.5f, 0.0f);
  set(0, 6, 0.5f, 0.0f);
  set(1, 0, kHuge, 0.05f);  // octant 0: e_s is ignored at a leaf → whole [0,3]
  set(2, 0, 0.0f, 0.5f);    // octant 1: coherent only over [2,3]
  set(2, 2, 0.0f, 0.05f);
  set(3, 5, 0.0f, 0.5f);   // octant 2: nothing coherent → [2,2] as a failed leaf
  set(4, 5, kHuge, 0.0f);  // octant 3: [2,2] coherent; at step 3 nothing is

  const ViewOrder pp = ViewOrder::orthographic({1, 1, 1});
  for (int t : {0, 1})
    EXPECT_EQ(traverse({.tree = tree, .step = t, .tol = tol, .errors = e, .view = pp}),
              (std::vector<Emitted>{{0, 1, {0, 1}}}));
  // Looking towards +x +y: octant 3 (upper x, upper y) is farthest, then 2, 1, 0.
  EXPECT_EQ(traverse({.tree = tree, .step = 2, .tol = tol, .errors = e, .view = pp}),
            (std::vector<Emitted>{{4, 5, {2, 2}}, {3, 5, {2, 2}}, {2, 2, {2, 3}}, {1, 0, {0, 3}}}));
  EXPECT_EQ(traverse({.tree = tree, .step = 3, .tol = tol, .errors = e, .view = pp}),
            (std::vector<Emitted>{{4, 6, {3, 3}}, {3, 6, {3, 3}}, {2, 2, {2, 3}}, {1, 0, {0, 3}}}));
  // Looking towards −x +y: farthest is octant 2 (lower x, upper y), then 3, 0, 1.
  EXPECT_EQ(traverse({.tree = tree,
                      .step = 2,
                      .tol = tol,
                      .errors = e,
                      .view = ViewOrder::orthographic({-1, 1, 0})}),
            (std::vector<Emitted>{{3, 5, {2, 2}}, {4, 5, {2, 2}}, {1, 0, {0, 3}}, {2, 2, {2, 3}}}));
  // Eye at x = 5 (upper x half; split plane x = 3), y = 1 (lower y): lower x, upper y farthest.
  EXPECT_EQ(traverse({.tree = tree,
                      .step = 2,
                      .tol = tol,
                      .errors = e,
                      .view = ViewOrder::perspective({5, 1, -10})}),
            (std::vector<Emitted>{{3, 5, {2, 2}}, {4, 5, {2, 2}}, {1, 0, {0, 3}}, {2, 2, {2, 3}}}));
}

TEST(Traverse, RandomErrorsTileTheVolumeOnceAndFollowTheRule) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const Grid& g : kGrids) {
    TspTree tree(g.dims, g.steps, g.brick);
    int mixed = 0;
    for (int trial = 0; trial < 6; ++trial) {
      const bool graded = trial % 2 == 1;
      NodeErrors e = random_errors(tree, rng, graded);
      const Tolerances tol =
          graded ? Tolerances{0.2 + 0.6 * u(rng), 0.2 + 0.6 * u(rng)} : Tolerances{u(rng), u(rng)};
      for (int t = 0; t < g.steps; ++t) {
        const std::string ctx =
            name(g) + " trial " + std::to_string(trial) + " t=" + std::to_string(t);
        auto out = traverse({.tree = tree, .step = t, .tol = tol, .errors = e, .view = kAnyView});
        expect_tiles_once(tree, out, ctx);
        expect_follows_rule(tree, t, tol, e, out, ctx);
        mixed += levels_of(tree, out) >= 2;
      }
    }
    EXPECT_GT(mixed, 0) << name(g) << ": no case mixed node sizes";
  }
}

// Our rule (issue 9 item 5): with the metric's transparency, no coherent node above the leaves is
// emitted while one of its children is transparent (it is drawn as its children, the transparent
// ones skipped as at zero tolerance); the output still tiles the volume once, every internal node
// emitted is coherent, and with nothing transparent it is the paper's traversal.
TEST(Traverse, CoherentNodesWithTransparentChildrenAreDrawnAsTheirChildren) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const Grid& g : kGrids) {
    TspTree tree(g.dims, g.steps, g.brick);
    const Octree& o = tree.octree();
    int descended = 0;
    for (int trial = 0; trial < 6; ++trial) {
      NodeErrors e = random_errors(tree, rng, true);
      // Transparent leaves at random, parents transparent when all their children are.
      std::vector<char> transparent(std::size_t(tree.size()), 0);
      for (int tau = 0; tau < tree.time().size(); ++tau)
        for (int id = o.size() - 1; id >= 0; --id) {
          bool all = true;
          for (int c : o.node(id).children)
            if (c >= 0) all &= transparent[std::size_t(tree.id(c, tau))] != 0;
          transparent[std::size_t(tree.id(id, tau))] =
              o.node(id).is_leaf() ? u(rng) < 0.4 : all;
        }
      const TransparentFn is_transparent = [&](int id) { return transparent[std::size_t(id)] != 0; };
      const TransparentFn nothing = [](int) { return false; };
      const Tolerances tol{0.3 + 0.6 * u(rng), 0.3 + 0.6 * u(rng)};
      for (int t = 0; t < g.steps; ++t) {
        const std::string ctx = name(g) + " trial " + std::to_string(trial) + " t=" + std::to_string(t);
        const auto paper =
            traverse({.tree = tree, .step = t, .tol = tol, .errors = e, .view = kAnyView});
        const auto ours = traverse({.tree = tree,
                                    .step = t,
                                    .tol = tol,
                                    .errors = e,
                                    .view = kAnyView,
                                    .transparent = is_transparent});
        expect_tiles_once(tree, ours, ctx);
        for (const Emitted& x : ours) {
          const OctreeNode& n = o.node(x.octree_id);
          if (n.is_leaf()) continue;
          const int id = tree.id(x.octree_id, x.time_id);
          EXPECT_LE(e.spatial[std::size_t(id)], tol.spatial) << ctx;  // still a coherent node
          EXPECT_LE(e.temporal[std::size_t(id)], tol.temporal) << ctx;
          if (transparent[std::size_t(id)]) continue;
          for (int c : n.children)
            if (c >= 0)
              EXPECT_FALSE(transparent[std::size_t(tree.id(c, x.time_id))])
                  << ctx << ": node " << x.octree_id << " drawn whole over a transparent child";
        }
        descended += ours.size() > paper.size();
        const auto same = traverse({.tree = tree,
                                    .step = t,
                                    .tol = tol,
                                    .errors = e,
                                    .view = kAnyView,
                                    .transparent = nothing});
        ASSERT_EQ(same.size(), paper.size()) << ctx;
        for (std::size_t k = 0; k < same.size(); ++k) {
          EXPECT_EQ(same[k].octree_id, paper[k].octree_id) << ctx;
          EXPECT_EQ(same[k].time_id, paper[k].time_id) << ctx;
        }
      }
    }
    EXPECT_GT(descended, 0) << name(g) << ": the rule never applied";
  }
}

// ---- back-to-front order --------------------------------------------------------------

TEST(ViewOrder, OrthographicFarthestOctantFollowsDirectionSigns) {
  Octree oct({64, 64, 64}, 8);
  for (int s = 0; s < 8; ++s) {
    std::array<double, 3> dir{s & 1 ? 0.3 : -0.7, s & 2 ? 2.0 : -1.0, s & 4 ? 1e-3 : -5.0};
    ViewOrder v = ViewOrder::orthographic(dir);
    EXPECT_FALSE(v.is_perspective());
    EXPECT_EQ(v.farthest_octant(oct, 0), s);
  }
}

TEST(ViewOrder, PerspectiveComparesEyeWithEachNodesSplitPlane) {
  Octree oct({64, 64, 64}, 8);  // 9 bricks of 7 cells per axis: the root splits at 5·7 = 35
  const OctreeNode& root = oct.node(0);
  ASSERT_EQ(oct.node(root.children[1]).box.lo[0], 35);
  ViewOrder v = ViewOrder::perspective({34.9, 35.1, -100});
  EXPECT_TRUE(v.is_perspective());
  EXPECT_EQ(v.farthest_octant(oct, 0), 0b101);
  // The lower-x child [0,35) splits at 3·7 = 21: x = 34.9 is now above the plane.
  const int c0 = root.children[0];
  ASSERT_EQ(oct.node(oct.node(c0).children[1]).box.lo[0], 21);
  EXPECT_EQ(v.farthest_octant(oct, c0) & 1, 0);
  EXPECT_EQ(ViewOrder::perspective({20, 0, 0}).farthest_octant(oct, c0) & 1, 1);
}

TEST(ViewOrder, UnsplitAxesNeverSetTheirBitAndChildrenListIsComplete) {
  Octree oct({7, 7, 4}, 4);  // z is not split anywhere
  for (auto v : {ViewOrder::orthographic({1, -1, 1}), ViewOrder::perspective({0, 9, -3})}) {
    // Both views put upper x and lower y farther; their z preference is dropped.
    EXPECT_EQ(v.farthest_octant(oct, 0), 0b001);
    ChildOrder kids = back_to_front_children(oct, 0, v);
    ASSERT_EQ(kids.count, 4);
    std::set<int> ids(kids.ids.begin(), kids.ids.begin() + 4);
    EXPECT_EQ(ids, (std::set<int>{1, 2, 3, 4}));
    EXPECT_EQ(kids.ids[0], oct.node(0).children[v.farthest_octant(oct, 0)]);
  }
  EXPECT_EQ(back_to_front_children(oct, 1, ViewOrder::orthographic({1, 1, 1})).count, 0);
}

std::vector<Viewer> orthographic_viewers(std::mt19937& rng) {
  std::uniform_real_distribution<double> mag(0.05, 1.0);
  std::vector<Viewer> views;
  for (int s = 0; s < 8; ++s) {
    std::array<double, 3> sign{s & 1 ? 1.0 : -1.0, s & 2 ? 1.0 : -1.0, s & 4 ? 1.0 : -1.0};
    views.push_back({false, sign});
    for (int k = 0; k < 2; ++k)
      views.push_back({false, {sign[0] * mag(rng), sign[1] * mag(rng), sign[2] * mag(rng)}});
  }
  views.push_back({false, {0, 0, 1}});
  views.push_back({false, {0, -1, 0.2}});
  return views;
}

std::vector<Viewer> perspective_viewers(const Dims& d, std::mt19937& rng) {
  std::vector<Viewer> views;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 6; ++k)  // inside the volume
    views.push_back({true, {u(rng) * (d.x - 1), u(rng) * (d.y - 1), u(rng) * (d.z - 1)}});
  for (int s = 0; s < 8; ++s)  // outside, beyond each corner
    views.push_back(
        {true,
         {s & 1 ? 2.0 * d.x : -d.x, s & 2 ? 2.5 * d.y : -0.5, s & 4 ? d.z + 0.5 : -3.0 * d.z}});
  views.push_back({true, {0.5 * d.x, 0.5 * d.y, -10.0 * d.z}});  // outside, facing a face
  return views;
}

ViewOrder make_view(const Viewer& v) {
  return v.perspective ? ViewOrder::perspective(v.v) : ViewOrder::orthographic(v.v);
}

std::string describe(const Viewer& v) {
  return std::string(v.perspective ? "eye " : "dir ") + std::to_string(v.v[0]) + "," +
         std::to_string(v.v[1]) + "," + std::to_string(v.v[2]);
}

void check_orders(const TspTree& tree, const NodeErrors& e, const Tolerances& tol,
                  const std::vector<Viewer>& views, const std::string& ctx) {
  for (const Viewer& view : views) {
    for (int t = 0; t < tree.time().steps(); ++t) {
      auto out =
          traverse({.tree = tree, .step = t, .tol = tol, .errors = e, .view = make_view(view)});
      EXPECT_EQ(order_violation(boxes_of(tree, out), view), "")
          << ctx << " " << describe(view) << " t=" << t;
    }
  }
}

TEST(BackToFront, AllLeavesInEveryOrthographicOctant) {
  std::mt19937 rng(3);
  for (const Grid& g : kGrids) {
    TspTree tree(g.dims, 1, g.brick);
    check_orders(tree, filled(tree, kHuge, kHuge), {0, 0}, orthographic_viewers(rng), name(g));
  }
}

TEST(BackToFront, MixedSizesOrthographicAndPerspective) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.2, 0.8);
  for (const Grid& g : kGrids) {
    TspTree tree(g.dims, 2, g.brick);
    int mixed = 0;
    for (int trial = 0; trial < 3; ++trial) {
      NodeErrors e = random_errors(tree, rng, true);
      const Tolerances tol{u(rng), u(rng)};
      for (int t = 0; t < 2; ++t)
        mixed +=
            levels_of(
                tree,
                traverse({.tree = tree, .step = t, .tol = tol, .errors = e, .view = kAnyView})) >=
            2;
      check_orders(tree, e, tol, orthographic_viewers(rng), name(g));
      check_orders(tree, e, tol, perspective_viewers(g.dims, rng), name(g));
    }
    EXPECT_GT(mixed, 0) << name(g) << ": no case mixed node sizes";
  }
}

TEST(BackToFront, AllLeavesPerspectiveInsideAndOutside) {
  std::mt19937 rng(5);
  for (const Grid& g : kGrids) {
    TspTree tree(g.dims, 1, g.brick);
    check_orders(tree, filled(tree, kHuge, kHuge), {0, 0}, perspective_viewers(g.dims, rng),
                 name(g));
  }
}

// The checker itself: it must reject reversed orders and accept hand-made correct ones.
TEST(BackToFront, CheckerRejectsReversedOrders) {
  std::mt19937 rng(9);
  TspTree tree({64, 64, 64}, 1, 8);
  NodeErrors e = filled(tree, kHuge, kHuge);
  std::vector<Viewer> views = orthographic_viewers(rng);
  for (const Viewer& v : perspective_viewers(tree.octree().dims(), rng)) views.push_back(v);
  for (const Viewer& view : views) {
    std::vector<Box> boxes = boxes_of(
        tree,
        traverse({.tree = tree, .step = 0, .tol = {0, 0}, .errors = e, .view = make_view(view)}));
    ASSERT_EQ(order_violation(boxes, view), "");
    std::reverse(boxes.begin(), boxes.end());
    EXPECT_NE(order_violation(boxes, view), "") << describe(view);
  }
  // Hand-made: two face neighbours along x, looking towards +x: the upper one goes first.
  const Box lo{{0, 0, 0}, {4, 4, 4}}, hi{{4, 0, 0}, {8, 4, 4}};
  const Viewer plus_x{false, {1, 0, 0}};
  EXPECT_EQ(order_violation({hi, lo}, plus_x), "");
  EXPECT_NE(order_violation({lo, hi}, plus_x), "");
  EXPECT_EQ(order_violation({lo, hi}, Viewer{false, {0, 1, 1}}), "");  // dir[x] = 0: either
  EXPECT_NE(order_violation({lo, hi}, Viewer{true, {2, 2, 2}}), "");   // eye inside lo
  EXPECT_EQ(order_violation({hi, lo}, Viewer{true, {2, 2, 2}}), "");
  EXPECT_EQ(order_violation({lo, hi}, Viewer{true, {4, 2, 2}}), "");  // eye on the shared face
  // A wrong order (one fixed order for every view) also fails for some view.
  int failures = 0;
  const auto fixed = boxes_of(tree, traverse({.tree = tree,
                                              .step = 0,
                                              .tol = {0, 0},
                                              .errors = e,
                                              .view = ViewOrder::orthographic({1, 1, 1})}));
  for (const Viewer& view : views) failures += order_violation(fixed, view).empty() ? 0 : 1;
  EXPECT_GT(failures, 0);
}

}  // namespace
}  // namespace tsp

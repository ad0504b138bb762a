#include "tsp/frame/frame_plan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "support/memory_tree.h"
#include "support/random_metric.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/lazy_errors.h"
#include "tsp/metric/tf_io.h"

namespace tsp {
namespace {

constexpr std::int64_t kUnlimited = std::int64_t(1) << 50;
const ViewOrder kView = ViewOrder::orthographic({0.4, -0.7, 0.6});

// Step t's frame traversed under errors and planned with info's classes, seen along kView
// (stops: a LOD cut or splat stops, given to both).
FramePlan traverse_and_plan(const TspTree& tree, int t, const NodeErrors& errors,
                            const NodeInfoFn& info, const Tolerances& tol, TextureCache& cache,
                            const std::vector<LodStop>& stops = {}) {
  return plan_frame({.tree = tree,
                     .step = t,
                     .emitted = traverse({.tree = tree,
                                          .step = t,
                                          .tol = tol,
                                          .errors = errors,
                                          .view = kView,
                                          .stops = stops}),
                     .info = info,
                     .tol = tol,
                     .view = kView,
                     .stops = stops},
                    cache);
}

TEST(FramePlan, ClassNamesAreTheFramesJsonNames) {
  EXPECT_STREQ(to_string(DrawClass::not_rendered), "not_rendered");
  EXPECT_STREQ(to_string(DrawClass::untextured), "untextured");
  EXPECT_STREQ(to_string(DrawClass::reused_texture), "reused_texture");
  EXPECT_STREQ(to_string(DrawClass::new_texture), "new_texture");
}

TEST(FramePlan, ShadingFollowsTransparencyThenSpatialTolerance) {
  const Tolerances tol{0.25, 9};
  EXPECT_EQ(shading_of({0.f, true}, tol), Shading::none);
  EXPECT_EQ(shading_of({5.f, true}, tol), Shading::none);
  EXPECT_EQ(shading_of({0.25f, false}, tol), Shading::flat);
  EXPECT_EQ(shading_of({0.2500001f, false}, tol), Shading::textured);
  EXPECT_EQ(shading_of({NAN, false}, tol), Shading::textured);
}

// 15 × 15 × 8 samples, 8-sample bricks: 2 × 2 × 1 bricks of 8³ stored samples whose own voxel
// boxes hold 7·7·8 = 392 (brick 0), 8·7·8 = 448 (bricks 1, 2) and 8·8·8 = 512 (brick 3) voxels.
// Two steps: time nodes 0 = [0, 1], 1 = [0, 0], 2 = [1, 1].
struct HandCase {
  TspTree tree{Dims{15, 15, 8}, 2, 8};
  std::map<int, NodeClassInfo> info;  // by TSP node id; others opaque with e_s 0
  NodeInfoFn fn() const {
    return [this](int id) {
      auto it = info.find(id);
      return it == info.end() ? NodeClassInfo{} : it->second;
    };
  }
  int leaf(int b) const { return tree.octree().brick_node(b); }
  std::vector<Emitted> frame(int t) const {
    const int leaf_time = t == 0 ? 1 : 2;
    return {{leaf(0), leaf_time, {t, t}},
            {leaf(1), 0, {0, 1}},
            {leaf(2), 0, {0, 1}},
            {leaf(3), leaf_time, {t, t}}};
  }
  HandCase() {
    for (int tau = 0; tau < 3; ++tau) {
      info[tree.id(leaf(0), tau)] = {0.f, true};   // NR
      info[tree.id(leaf(1), tau)] = {0.f, false};  // UP
      info[tree.id(leaf(2), tau)] = {0.5f, false};
      info[tree.id(leaf(3), tau)] = {0.5f, false};
    }
  }
};

TEST(FramePlan, HandBuiltFramesGetTheirClassesTexturesAndShares) {
  HandCase hc;
  ASSERT_EQ(hc.tree.octree().brick_count(), 4);
  const Tolerances tol{0.1, 0.1};
  for (CachePolicy policy : {CachePolicy::on, CachePolicy::off}) {
    TextureCache cache(kUnlimited, policy);
    const FramePlan p0 = plan_frame({.tree = hc.tree,
                                     .step = 0,
                                     .emitted = hc.frame(0),
                                     .info = hc.fn(),
                                     .tol = tol,
                                     .view = kView},
                                    cache);
    ASSERT_EQ(p0.nodes.size(), 4u);
    EXPECT_EQ(p0.step, 0);
    EXPECT_EQ(p0.nodes[0].cls, DrawClass::not_rendered);
    EXPECT_EQ(p0.nodes[1].cls, DrawClass::untextured);
    EXPECT_EQ(p0.nodes[2].cls, DrawClass::new_texture);
    EXPECT_EQ(p0.nodes[3].cls, DrawClass::new_texture);
    EXPECT_EQ(p0.nodes[0].voxels, 392);
    EXPECT_EQ(p0.nodes[3].voxels, 512);
    EXPECT_EQ(p0.nodes[0].texture_count, 0);
    EXPECT_EQ(p0.nodes[1].texture_count, 0);
    ASSERT_EQ(p0.textures.size(), 2u);
    EXPECT_EQ(p0.nodes[2].first_texture, 0);
    EXPECT_EQ(p0.nodes[3].first_texture, 1);
    EXPECT_EQ(p0.textures[0].key, (TextureKey{2, 0, 0}));  // span [0, 1]'s middle step, 0
    EXPECT_EQ(p0.textures[1].key, (TextureKey{3, 0, 0}));
    EXPECT_TRUE(p0.textures[0].upload && p0.textures[1].upload);
    EXPECT_EQ(p0.textures[0].bytes, 8 * 8 * 8 * 2);
    EXPECT_EQ(p0.uploads, 2);
    EXPECT_EQ(p0.bytes_uploaded, 2 * 1024);
    EXPECT_EQ(p0.textures_resident, 2);
    EXPECT_EQ(p0.texture_bytes, 2 * 1024);
    EXPECT_EQ(p0.total_voxels, 15 * 15 * 8);
    EXPECT_EQ(p0.class_voxels, (std::array<std::int64_t, 5>{392, 448, 0, 448 + 512, 0}));
    EXPECT_DOUBLE_EQ(p0.percent(DrawClass::not_rendered), 100.0 * 392 / 1800);
    EXPECT_DOUBLE_EQ(p0.percent(DrawClass::new_texture), 100.0 * 960 / 1800);

    // Step 1: brick 2's span [0, 1] texture is reused; brick 3 needs the one of [1, 1].
    const FramePlan p1 = plan_frame({.tree = hc.tree,
                                     .step = 1,
                                     .emitted = hc.frame(1),
                                     .info = hc.fn(),
                                     .tol = tol,
                                     .view = kView},
                                    cache);
    EXPECT_EQ(p1.nodes[2].cls, DrawClass::reused_texture);
    EXPECT_EQ(p1.nodes[3].cls, DrawClass::new_texture);
    EXPECT_EQ(p1.textures[1].key, (TextureKey{3, 1, 0}));
    EXPECT_EQ(p1.class_voxels, (std::array<std::int64_t, 5>{392, 448, 448, 512, 0}));
    EXPECT_DOUBLE_EQ(p1.percent(DrawClass::reused_texture), 100.0 * 448 / 1800);
    EXPECT_EQ(p1.uploads, 1);
    EXPECT_TRUE(p1.evict_before.empty());
    if (policy == CachePolicy::off) {
      EXPECT_EQ(p1.release_after, (std::vector<TextureKey>{{3, 0, 0}}));
      EXPECT_EQ(p1.textures_resident, 2);
    } else {
      EXPECT_TRUE(p1.release_after.empty());
      EXPECT_EQ(p1.textures_resident, 3);
    }
  }
}

TEST(FramePlan, TexturedInternalNodeIsDrawnByItsLeafBricksBackToFront) {
  HandCase hc;
  hc.info[hc.tree.id(0, 0)] = {0.5f, false};  // the root, span [0, 1], textured
  const std::vector<Emitted> root = {{0, 0, {0, 1}}};
  TextureCache cache(kUnlimited, CachePolicy::on);
  const Tolerances tol{0.1, 0.1};
  // Looking along +x+y the upper-x, upper-y brick (3) is farthest; along −x−y brick 0 is.
  const ViewOrder up = ViewOrder::orthographic({1, 1, 1});
  const ViewOrder down = ViewOrder::orthographic({-1, -1, 1});
  EXPECT_EQ(leaf_bricks(hc.tree.octree(), 0, up), (std::vector<int>{3, 2, 1, 0}));
  EXPECT_EQ(leaf_bricks(hc.tree.octree(), 0, down), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(leaf_bricks(hc.tree.octree(), hc.leaf(2), down), (std::vector<int>{2}));

  const FramePlan a = plan_frame(
      {.tree = hc.tree, .step = 1, .emitted = root, .info = hc.fn(), .tol = tol, .view = up},
      cache);
  ASSERT_EQ(a.nodes.size(), 1u);
  EXPECT_EQ(a.nodes[0].cls, DrawClass::new_texture);
  EXPECT_EQ(a.nodes[0].voxels, 1800);
  ASSERT_EQ(a.nodes[0].texture_count, 4);
  std::vector<int> bricks;
  for (const PlannedTexture& t : a.textures) {
    bricks.push_back(t.key.brick);
    EXPECT_EQ(t.key.t0, 0);  // the span's first step
    EXPECT_TRUE(t.upload);
  }
  EXPECT_EQ(bricks, (std::vector<int>{3, 2, 1, 0}));
  EXPECT_DOUBLE_EQ(a.percent(DrawClass::new_texture), 100.0);

  const FramePlan b = plan_frame(
      {.tree = hc.tree, .step = 0, .emitted = root, .info = hc.fn(), .tol = tol, .view = down},
      cache);
  EXPECT_EQ(b.nodes[0].cls, DrawClass::reused_texture);
  EXPECT_EQ(b.uploads, 0);

  // One of the four textures gone: the node is NT, uploading only that one.
  cache.drop_unreachable([](const TextureKey& k) { return k.brick != 1; });
  const FramePlan c = plan_frame(
      {.tree = hc.tree, .step = 0, .emitted = root, .info = hc.fn(), .tol = tol, .view = down},
      cache);
  EXPECT_EQ(c.nodes[0].cls, DrawClass::new_texture);
  EXPECT_EQ(c.uploads, 1);
  EXPECT_TRUE(c.textures[1].upload);
  EXPECT_EQ(c.textures[1].key.brick, 1);
}

TEST(FramePlan, SharesSumTo100AndMatchTheTraversalsOutput) {
  const TspTree tree({40, 33, 17}, 7, 8);
  std::mt19937 rng(77);
  TextureCache cache(20 * 8 * 8 * 8 * 2, CachePolicy::on);
  std::uniform_real_distribution<double> tol_u(0, 1.5);
  int textured_frames = 0, flat_frames = 0, hidden_frames = 0;
  for (int round = 0; round < 60; ++round) {
    const MetricResult m = tsptest::random_metric(tree, rng, 0.2f);
    const Tolerances tol{round % 5 == 0 ? 0.0 : tol_u(rng), tol_u(rng)};
    const int t = int(rng() % 7);
    const std::vector<Emitted> out =
        traverse({.tree = tree, .step = t, .tol = tol, .errors = m.errors, .view = kView});
    const FramePlan plan = plan_frame(
        {.tree = tree, .step = t, .emitted = out, .info = node_info(m), .tol = tol, .view = kView},
        cache);
    ASSERT_EQ(plan.nodes.size(), out.size());
    std::array<std::int64_t, kDrawClassCount> want{};
    std::int64_t uploads = 0;
    for (std::size_t i = 0; i < out.size(); ++i) {
      const PlannedNode& p = plan.nodes[i];
      ASSERT_EQ(p.node, out[i]);  // same nodes, same back-to-front order
      const int id = tree.id(out[i].octree_id, out[i].time_id);
      const Box b = tree.octree().node(out[i].octree_id).box;
      const std::int64_t voxels =
          std::int64_t(b.hi[0] - b.lo[0]) * (b.hi[1] - b.lo[1]) * (b.hi[2] - b.lo[2]);
      ASSERT_EQ(p.voxels, voxels);
      DrawClass c;
      if (m.transparent[id]) {
        c = DrawClass::not_rendered;
      } else if (m.errors.spatial[id] <= tol.spatial) {
        c = DrawClass::untextured;
      } else {
        bool any_upload = false;
        for (int k = 0; k < p.texture_count; ++k)
          any_upload = any_upload || plan.textures[p.first_texture + k].upload;
        c = any_upload ? DrawClass::new_texture : DrawClass::reused_texture;
        ASSERT_GE(p.texture_count, 1);
      }
      ASSERT_EQ(p.cls, c);
      if (tol.spatial == 0 && c == DrawClass::untextured) {
        ASSERT_EQ(m.errors.spatial[id], 0.f);
      }
      want[int(c)] += voxels;
    }
    for (const PlannedTexture& pt : plan.textures) uploads += pt.upload;
    EXPECT_EQ(plan.class_voxels, want);
    EXPECT_EQ(plan.total_voxels, tree.octree().dims().count());
    double sum = 0;
    for (int c = 0; c < kDrawClassCount; ++c) sum += plan.percent(DrawClass(c));
    EXPECT_NEAR(sum, 100.0, 1e-9);
    EXPECT_EQ(plan.uploads, uploads);
    textured_frames += want[2] + want[3] > 0;
    flat_frames += want[1] > 0;
    hidden_frames += want[0] > 0;
  }
  EXPECT_GT(textured_frames, 20);
  EXPECT_GT(flat_frames, 20);
  EXPECT_GT(hidden_frames, 20);
}

TEST(FramePlan, ZeroSpatialToleranceDrawsFlatOnlyWhereTheErrorIsExactlyZero) {
  // Data constant in the lower-x bricks, noisy elsewhere: real scalar errors, some exactly 0.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(1, 2);
  auto s = tsptest::MemorySeries::generate(
      {30, 16, 9}, 4, [&](int, int x, int, int) { return x < 15 ? 3.0f : u(rng); });
  tsptest::MemoryBrickStore store(s, 8);
  const TspTree& tree = store.tree();
  const TransferFunction tf = preset_transfer_function("filled", tree.value_range());
  const MetricResult m = compute_errors(Metric::scalar, tree, tf, nullptr, 1);
  const Tolerances tol{0, 0};
  TextureCache cache(kUnlimited, CachePolicy::off);
  int flat = 0, textured = 0;
  for (int t = 0; t < 4; ++t) {
    const auto out =
        traverse({.tree = tree, .step = t, .tol = tol, .errors = m.errors, .view = kView});
    const FramePlan plan = plan_frame(
        {.tree = tree, .step = t, .emitted = out, .info = node_info(m), .tol = tol, .view = kView},
        cache);
    for (const PlannedNode& p : plan.nodes) {
      const int id = tree.id(p.node.octree_id, p.node.time_id);
      if (m.transparent[id]) continue;
      EXPECT_EQ(p.cls == DrawClass::untextured, m.errors.spatial[id] == 0.f);
      flat += p.cls == DrawClass::untextured;
      textured += p.texture_count > 0;
    }
  }
  EXPECT_GT(flat, 0);
  EXPECT_GT(textured, 0);
}

TEST(FramePlan, ReachableTexturesAreTheUnionOfEveryStepsTextures) {
  const TspTree tree({40, 33, 17}, 9, 8);
  std::mt19937 rng(8);
  for (int round = 0; round < 10; ++round) {
    const MetricResult m = tsptest::random_metric(tree, rng, 0.2f);
    const Tolerances tol{0.2 + 0.1 * round, 0.3 + 0.05 * round};
    TextureCache cache(kUnlimited, CachePolicy::on);
    TextureKeySet drawn;
    for (int t = 0; t < tree.time().steps(); ++t) {
      const FramePlan plan = traverse_and_plan(tree, t, m.errors, node_info(m), tol, cache);
      for (const PlannedTexture& pt : plan.textures) drawn.insert(pt.key);
    }
    EXPECT_EQ(reachable_textures(tree, m, tol, false), drawn);
    EXPECT_EQ(std::int64_t(drawn.size()), cache.stats().resident_count);
    // Keeping the reachable set of these tolerances drops nothing.
    EXPECT_TRUE(cache.drop_unreachable(reachable_textures(tree, m, tol, false)).empty());
  }
}

// Splat stops (tsp/lod/splat_cut.h): every node the traversal would texture at a splat stop is
// drawn flat instead, and no texture is requested or reachable; the other nodes keep their class.
TEST(FramePlan, SplatStopsAreDrawnFlatWithoutTextures) {
  const TspTree tree({40, 33, 17}, 9, 8);
  std::mt19937 rng(9);
  const MetricResult m = tsptest::random_metric(tree, rng, 0.2f);
  const Tolerances tol{0, 0.5};  // flat only where the spatial error is exactly 0
  const Octree& o = tree.octree();
  // The root's children are splats (a cut one level down).
  std::vector<LodStop> stops(std::size_t(o.size()), LodStop::none);
  for (int c : o.node(0).children)
    if (c >= 0) stops[std::size_t(c)] = LodStop::splat;
  std::vector<LodStop> cut = stops;
  for (LodStop& s : cut) s = s != LodStop::none ? LodStop::cut : LodStop::none;
  int textured_nodes = 0;
  for (int t = 0; t < tree.time().steps(); ++t) {
    TextureCache cache(kUnlimited, CachePolicy::on), cache_cut(kUnlimited, CachePolicy::on);
    const FramePlan splats = traverse_and_plan(tree, t, m.errors, node_info(m), tol, cache, stops);
    const FramePlan textured = traverse_and_plan(tree, t, m.errors, node_info(m), tol, cache_cut, cut);
    ASSERT_EQ(splats.nodes.size(), textured.nodes.size());
    EXPECT_TRUE(splats.textures.empty());
    textured_nodes += int(textured.textures.size());

    for (std::size_t k = 0; k < splats.nodes.size(); ++k) {
      const DrawClass want = textured.nodes[k].cls == DrawClass::new_texture ||
                                     textured.nodes[k].cls == DrawClass::reused_texture
                                 ? DrawClass::untextured
                                 : textured.nodes[k].cls;
      EXPECT_EQ(splats.nodes[k].cls, want) << "step " << t << " node " << k;
    }
  }
  EXPECT_GT(textured_nodes, 0);  // the same cut, not splats, textures some nodes
  EXPECT_TRUE(reachable_textures(tree, m, tol, false, SpanStep::middle, stops).empty());
}

// The upload budget is an input of the plan: the first upload always goes ahead, the textures
// over the budget are deferred (never entered in the cache), and later frames complete them.
TEST(FramePlan, UploadBudgetDefersTexturesWithoutEnteringTheCache) {
  HandCase hc;
  const Tolerances tol{0.1, 0.1};
  TextureCache cache(kUnlimited, CachePolicy::on);
  // Step 0's hand-built frame planned under an upload budget of `bytes`.
  auto planned = [&](std::int64_t bytes, TextureCache& in) {
    return plan_frame({.tree = hc.tree,
                       .step = 0,
                       .emitted = hc.frame(0),
                       .info = hc.fn(),
                       .tol = tol,
                       .view = kView,
                       .upload_budget = bytes},
                      in);
  };
  // Budget below one texture (1024 bytes): one upload per frame.
  const FramePlan p0 = planned(1, cache);
  ASSERT_EQ(p0.textures.size(), 2u);
  EXPECT_TRUE(p0.textures[0].upload);
  EXPECT_FALSE(p0.textures[0].deferred);
  EXPECT_FALSE(p0.textures[1].upload);
  EXPECT_TRUE(p0.textures[1].deferred);
  EXPECT_EQ(p0.uploads, 1);
  EXPECT_EQ(p0.deferred, 1);
  EXPECT_EQ(p0.bytes_uploaded, 1024);
  EXPECT_EQ(p0.textures_resident, 1);
  EXPECT_FALSE(cache.contains(p0.textures[1].key));
  // The node whose texture waits still counts as new data, as it will be once it arrives.
  EXPECT_EQ(p0.nodes[3].cls, DrawClass::new_texture);
  EXPECT_TRUE(p0.evict_before.empty());
  // The same frame again: the first texture is resident, the second is uploaded now.
  const FramePlan again = planned(1, cache);
  EXPECT_FALSE(again.textures[0].upload);
  EXPECT_TRUE(again.textures[1].upload);
  EXPECT_EQ(again.deferred, 0);
  EXPECT_EQ(again.textures_resident, 2);
  // A budget that holds both defers nothing; no budget (0) neither.
  TextureCache roomy(kUnlimited, CachePolicy::on), unlimited(kUnlimited, CachePolicy::on);
  EXPECT_EQ(planned(2048, roomy).deferred, 0);
  EXPECT_EQ(planned(0, unlimited).deferred, 0);
}

// A whole-tree metric and the live LazyErrors serve frames the same classes and colours.
TEST(FramePlan, WholeTreeAndLiveMetricsPlanTheSameFrames) {
  auto s = tsptest::MemorySeries::generate({24, 20, 12}, 5, [](int t, int x, int y, int z) {
    return float(std::sin(0.3 * x + 0.2 * t) + 0.1 * y - 0.05 * z);
  });
  tsptest::MemoryBrickStore store(s, 8);
  const TspTree& tree = store.tree();
  const TransferFunction tf = preset_transfer_function("sparse", tree.value_range());
  const MetricResult m = compute_errors(Metric::approximate, tree, tf, nullptr, 1);
  WholeTreeMetric whole(m);
  LazyErrors live(tree, Metric::approximate, tf);
  const Tolerances tol{0.05, 0.05};
  for (int t = 0; t < 5; ++t) {
    TextureCache a(kUnlimited, CachePolicy::off), b(kUnlimited, CachePolicy::off);
    const FramePlan pa =
        traverse_and_plan(tree, t, whole.errors_for_step(t), node_info(whole), tol, a);
    const FramePlan pb = traverse_and_plan(tree, t, live.errors_for_step(t), node_info(live), tol, b);
    ASSERT_EQ(pa.nodes.size(), pb.nodes.size());
    EXPECT_EQ(pa.class_voxels, pb.class_voxels);
    for (const PlannedNode& n : pb.nodes) {
      const int id = tree.id(n.node.octree_id, n.node.time_id);
      const Rgba x = whole.mean_colour(id), y = live.mean_colour(id);
      EXPECT_FLOAT_EQ(x.r, y.r);
      EXPECT_FLOAT_EQ(x.a, y.a);
    }
  }
  EXPECT_EQ(reachable_textures(tree, whole, tol, false),
            reachable_textures(tree, live, tol, false));
}

}  // namespace
}  // namespace tsp

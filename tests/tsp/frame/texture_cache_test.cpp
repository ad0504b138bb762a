#include "tsp/frame/texture_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "support/memory_tree.h"
#include "support/random_metric.h"
#include "tsp/core/error.h"
#include "tsp/frame/frame_plan.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/tree/traversal.h"

namespace tsp {
namespace {

constexpr std::int64_t kUnlimited = std::int64_t(1) << 50;
constexpr std::int64_t kSize = 100;  // bytes of every texture in the hand-built cases

TextureKey key(int brick, int t0 = 0) {
  return TextureKey{brick, t0, 0};
}

std::set<int> bricks_of(const std::vector<TextureKey>& keys) {
  std::set<int> out;
  for (const TextureKey& k : keys) out.insert(k.brick);
  return out;
}

// Runs one frame requesting `bricks` (span start 0): returns which were hits.
std::vector<bool> frame(TextureCache& c, const std::vector<int>& bricks,
                        std::vector<TextureKey>* released = nullptr) {
  c.begin_frame();
  std::vector<bool> hits;
  for (int b : bricks) hits.push_back(c.request(key(b), kSize).hit);
  std::vector<TextureKey> r = c.end_frame();
  if (released) *released = r;
  return hits;
}

TEST(TextureCache, RequestsKeepLeastRecentlyUsedOrder) {
  TextureCache c(kUnlimited, CachePolicy::on);
  EXPECT_EQ(frame(c, {1, 2, 3}), (std::vector<bool>{false, false, false}));
  EXPECT_EQ(c.lru_order(), (std::vector<TextureKey>{key(3), key(2), key(1)}));
  EXPECT_EQ(frame(c, {1}), (std::vector<bool>{true}));
  EXPECT_EQ(c.lru_order(), (std::vector<TextureKey>{key(1), key(3), key(2)}));
  const TextureCacheStats& s = c.stats();
  EXPECT_EQ(s.hits, 1);
  EXPECT_EQ(s.misses, 3);
  EXPECT_EQ(s.frame_hits, 1);
  EXPECT_EQ(s.frame_misses, 0);
  EXPECT_EQ(s.frame_uploaded_bytes, 0);
  EXPECT_EQ(s.resident_count, 3);
  EXPECT_EQ(s.resident_bytes, 3 * kSize);
}

TEST(TextureCache, KeysDifferBySpanStartAndLevel) {
  TextureCache c(kUnlimited, CachePolicy::on);
  c.begin_frame();
  EXPECT_FALSE(c.request({4, 0, 0}, kSize).hit);
  EXPECT_FALSE(c.request({4, 2, 0}, kSize).hit);
  EXPECT_FALSE(c.request({4, 0, 1}, kSize).hit);
  EXPECT_TRUE(c.request({4, 2, 0}, kSize).hit);  // second request in one frame
  c.end_frame();
  EXPECT_EQ(c.stats().resident_count, 3);
  TextureKeyHash h;
  EXPECT_NE(h({4, 0, 0}), h({4, 2, 0}));
}

TEST(TextureCache, EvictsLeastRecentlyUsedToStayWithinBudget) {
  TextureCache c(3 * kSize, CachePolicy::on);
  frame(c, {1, 2, 3});
  c.begin_frame();
  TextureRequest r = c.request(key(4), kSize);  // full: the oldest (1) goes
  EXPECT_FALSE(r.hit);
  EXPECT_EQ(r.evicted, (std::vector<TextureKey>{key(1)}));
  EXPECT_TRUE(c.request(key(2), kSize).hit);  // 2 becomes recent, so 3 is next
  r = c.request(key(5), kSize);
  EXPECT_EQ(r.evicted, (std::vector<TextureKey>{key(3)}));
  EXPECT_TRUE(c.end_frame().empty());
  EXPECT_EQ(c.stats().resident_bytes, 3 * kSize);
  EXPECT_EQ(c.stats().evictions, 2);
  EXPECT_EQ(bricks_of(c.lru_order()), (std::set<int>{2, 4, 5}));
}

TEST(TextureCache, FrameNeedingMoreThanTheBudgetKeepsItsTexturesUntilItEnds) {
  // Our rule: a frame's textures are pinned, so the cache exceeds the budget during that frame;
  // end_frame trims it back, oldest request of the frame first.
  TextureCache c(2 * kSize, CachePolicy::on);
  frame(c, {9});
  c.begin_frame();
  EXPECT_TRUE(c.request(key(1), kSize).evicted.empty());
  TextureRequest r = c.request(key(2), kSize);
  EXPECT_EQ(r.evicted, (std::vector<TextureKey>{key(9)}));  // the only unpinned one
  EXPECT_TRUE(c.request(key(3), kSize).evicted.empty());    // over budget: nothing to evict
  EXPECT_TRUE(c.request(key(4), kSize).evicted.empty());
  EXPECT_EQ(c.stats().resident_bytes, 4 * kSize);
  EXPECT_EQ(c.stats().peak_bytes, 4 * kSize);
  EXPECT_TRUE(c.request(key(1), kSize).hit);  // still there
  EXPECT_EQ(c.end_frame(), (std::vector<TextureKey>{key(2), key(3)}));
  EXPECT_EQ(c.lru_order(), (std::vector<TextureKey>{key(1), key(4)}));
}

TEST(TextureCache, TextureLargerThanTheBudgetLivesOnlyForItsFrame) {
  TextureCache c(kSize / 2, CachePolicy::on);
  c.begin_frame();
  EXPECT_FALSE(c.request(key(1), kSize).hit);
  EXPECT_TRUE(c.contains(key(1)));
  EXPECT_EQ(c.end_frame(), (std::vector<TextureKey>{key(1)}));
  EXPECT_EQ(c.stats().resident_count, 0);
}

TEST(TextureCache, ZeroBudgetWithCacheOnStillDrawsEveryFrame) {
  TextureCache c(0, CachePolicy::on);
  EXPECT_EQ(frame(c, {1, 2}), (std::vector<bool>{false, false}));
  EXPECT_EQ(frame(c, {1, 2}), (std::vector<bool>{false, false}));
  EXPECT_EQ(c.stats().resident_bytes, 0);
}

TEST(TextureCache, NegativeBudgetIsAUsageError) {
  EXPECT_THROW(TextureCache(-1, CachePolicy::on), UsageError);
  TextureCache c(10, CachePolicy::off);
  EXPECT_THROW(c.set_budget(-5), UsageError);
}

// Spec §8 on a step sequence: a brick whose span [0, 3] is drawn at steps 0–3, then single-step
// textures, then a jump back to step 1.
struct Step {
  int step;
  std::vector<TextureKey> keys;
};
const std::vector<Step> kSequence = {
    {0, {key(0, 0), key(1, 0)}},  // brick 0 span [0,3]; brick 1 span [0,0]
    {1, {key(0, 0), key(1, 1)}}, {2, {key(0, 0), key(1, 2)}}, {3, {key(0, 0), key(1, 3)}},
    {4, {key(0, 4), key(1, 4)}}, {1, {key(0, 0), key(1, 1)}},  // jump back
};

std::vector<std::vector<bool>> run_sequence(TextureCache& c,
                                            std::vector<std::vector<TextureKey>>* released) {
  std::vector<std::vector<bool>> hits;
  for (const Step& s : kSequence) {
    c.begin_frame();
    hits.emplace_back();
    for (const TextureKey& k : s.keys) hits.back().push_back(c.request(k, kSize).hit);
    released->push_back(c.end_frame());
  }
  return hits;
}

// The hits of kSequence's first five frames, the same under either policy (consecutive frames
// draw each span's texture); only the jump back differs.
const std::vector<std::vector<bool>> kFirstFiveHits{
    {false, false}, {true, false}, {true, false}, {true, false}, {false, false}};

TEST(TextureCache, CacheOffKeepsASpanTextureOnlyWhileConsecutiveFramesDrawIt) {
  TextureCache c(kUnlimited, CachePolicy::off);
  std::vector<std::vector<TextureKey>> released;
  const auto hits = run_sequence(c, &released);
  ASSERT_EQ(hits.size(), 6u);
  EXPECT_EQ(std::vector(hits.begin(), hits.begin() + 5), kFirstFiveHits);
  EXPECT_EQ(hits[5], (std::vector<bool>{false, false}));  // the jump back finds neither
  using K = std::vector<TextureKey>;
  EXPECT_EQ(released, (std::vector<K>{{},
                                      {key(1, 0)},
                                      {key(1, 1)},
                                      {key(1, 2)},
                                      {key(1, 3), key(0, 0)},
                                      {key(1, 4), key(0, 4)}}));
  EXPECT_EQ(c.stats().resident_count, 2);
}

TEST(TextureCache, CacheOnKeepsTexturesAcrossTheWholeSequence) {
  TextureCache c(kUnlimited, CachePolicy::on);
  std::vector<std::vector<TextureKey>> released;
  const auto hits = run_sequence(c, &released);
  ASSERT_EQ(hits.size(), 6u);
  EXPECT_EQ(std::vector(hits.begin(), hits.begin() + 5), kFirstFiveHits);
  EXPECT_EQ(hits[5], (std::vector<bool>{true, true}));  // the jump back finds both
  for (const auto& r : released) EXPECT_TRUE(r.empty());
  EXPECT_EQ(c.stats().resident_count, 7);
  EXPECT_EQ(c.stats().hits, 5);
  EXPECT_EQ(c.stats().misses, 7);
}

TEST(TextureCache, SwitchingPolicyTakesEffectAtTheNextFrameEnd) {
  TextureCache c(kUnlimited, CachePolicy::on);
  frame(c, {1, 2, 3});
  c.set_policy(CachePolicy::off);
  std::vector<TextureKey> released;
  EXPECT_EQ(frame(c, {2}, &released), (std::vector<bool>{true}));
  EXPECT_EQ(bricks_of(released), (std::set<int>{1, 3}));
}

TEST(TextureCache, ShrinkingTheBudgetEvictsLeastRecentlyUsed) {
  TextureCache c(kUnlimited, CachePolicy::on);
  frame(c, {1, 2, 3});
  EXPECT_EQ(c.set_budget(kSize), (std::vector<TextureKey>{key(1), key(2)}));
  EXPECT_EQ(c.lru_order(), (std::vector<TextureKey>{key(3)}));
  EXPECT_EQ(c.clear(), (std::vector<TextureKey>{key(3)}));
  EXPECT_EQ(c.stats().resident_bytes, 0);
}

TEST(TextureCache, DropUnreachableKeepsExactlyTheReachableSet) {
  TextureCache c(kUnlimited, CachePolicy::on);
  frame(c, {1, 2, 3, 4});
  EXPECT_EQ(bricks_of(c.drop_unreachable(TextureKeySet{key(2), key(4), key(7)})),
            (std::set<int>{1, 3}));
  EXPECT_EQ(bricks_of(c.lru_order()), (std::set<int>{2, 4}));
  EXPECT_EQ(c.drop_unreachable([](const TextureKey& k) { return k.brick == 4; }),
            (std::vector<TextureKey>{key(2)}));
  EXPECT_EQ(c.stats().resident_bytes, kSize);
  EXPECT_EQ(c.stats().evictions, 3);
}

// ---- whole frames on a real tree ------------------------------------------------------

// Textures (brick, span start) a frame draws, found without the library's planner: every brick
// whose box lies inside a textured emitted node's box.
std::vector<TextureKey> drawn_textures(const TspTree& tree, const std::vector<Emitted>& out,
                                       const MetricResult& m, const Tolerances& tol) {
  const Octree& oct = tree.octree();
  std::vector<TextureKey> keys;
  for (const Emitted& e : out) {
    const int id = tree.id(e.octree_id, e.time_id);
    if (m.transparent[id] || m.errors.spatial[id] <= tol.spatial) continue;
    const Box nb = oct.node(e.octree_id).box;
    for (int b = 0; b < oct.brick_count(); ++b) {
      const Box bb = oct.brick_box(b);
      bool inside = true;
      for (int a = 0; a < 3; ++a) inside = inside && bb.lo[a] >= nb.lo[a] && bb.hi[a] <= nb.hi[a];
      // The default representative step: the span's middle, ⌊(t0 + t1)/2⌋.
      if (inside) keys.push_back(TextureKey{b, (e.span.t0 + e.span.t1) / 2, 0});
    }
  }
  return keys;
}

// Brute-force model of spec §8 with our budget rules: a flat list scanned linearly.
class Model {
 public:
  Model(std::int64_t budget, CachePolicy policy) : budget_(budget), policy_(policy) {}
  void begin() { ++frame_; }
  bool request(const TextureKey& k, std::int64_t bytes) {
    ++clock_;
    for (Item& it : items_)
      if (it.key == k) {
        it.used = clock_;
        it.frame = frame_;
        return true;
      }
    while (bytes_() + bytes > budget_) {
      auto victim = items_.end();
      for (auto it = items_.begin(); it != items_.end(); ++it)
        if (it->frame != frame_ && (victim == items_.end() || it->used < victim->used)) victim = it;
      if (victim == items_.end()) break;
      items_.erase(victim);
    }
    items_.push_back({k, bytes, clock_, frame_});
    return false;
  }
  void end() {
    if (policy_ == CachePolicy::off)
      std::erase_if(items_, [&](const Item& it) { return it.frame != frame_; });
    while (bytes_() > budget_)
      items_.erase(std::min_element(items_.begin(), items_.end(),
                                    [](auto& a, auto& b) { return a.used < b.used; }));
  }
  void keep_only(const TextureKeySet& keep) {
    std::erase_if(items_, [&](const Item& it) { return !keep.count(it.key); });
  }
  std::set<std::tuple<int, int, int>> resident() const {
    std::set<std::tuple<int, int, int>> s;
    for (const Item& it : items_) s.insert({it.key.brick, it.key.t0, it.key.level});
    return s;
  }

 private:
  struct Item {
    TextureKey key;
    std::int64_t bytes;
    std::int64_t used;
    std::int64_t frame;
  };
  std::int64_t budget_;
  CachePolicy policy_;
  std::vector<Item> items_;
  std::int64_t clock_ = 0, frame_ = 0;
  std::int64_t bytes_() const {
    std::int64_t s = 0;
    for (const Item& it : items_) s += it.bytes;
    return s;
  }
};

// Stored samples of brick b, counted from its box.
std::int64_t samples_of(const TspTree& tree, int b) {
  const Box sb = tree.octree().brick_samples(b);
  return std::int64_t(sb.hi[0] - sb.lo[0]) * (sb.hi[1] - sb.lo[1]) * (sb.hi[2] - sb.lo[2]);
}

std::set<std::tuple<int, int, int>> resident_of(const TextureCache& c) {
  std::set<std::tuple<int, int, int>> s;
  for (const TextureKey& k : c.lru_order()) s.insert({k.brick, k.t0, k.level});
  return s;
}

// Reachable textures under tol over all steps, by the brute-force drawn_textures.
TextureKeySet brute_reachable(const TspTree& tree, const MetricResult& m, const Tolerances& tol) {
  TextureKeySet keys;
  for (int t = 0; t < tree.time().steps(); ++t)
    for (const TextureKey& k : drawn_textures(tree,
                                              traverse({.tree = tree,
                                              .step = t,
                                              .tol = tol,
                                              .errors = m.errors,
                                              .view = ViewOrder::orthographic({1, 0, 0})}),
                                              m, tol))
      keys.insert(k);
  return keys;
}

TEST(TextureCache, HitsAndMissesEqualABruteForceModelOverRandomTraversals) {
  const TspTree tree({40, 33, 17}, 9, 8);  // 5 × 4 × 2 bricks, time tree over 9 steps
  std::mt19937 rng(20250611);
  const std::int64_t brick_bytes = samples_of(tree, 0) * 2;  // the largest brick
  const std::int64_t budgets[] = {kUnlimited, 6 * brick_bytes, 17 * brick_bytes, 0};
  int frames_with_hits = 0, frames_with_evictions = 0;
  for (int round = 0; round < 12; ++round) {
    const MetricResult m = tsptest::random_metric(tree, rng);
    for (CachePolicy policy : {CachePolicy::on, CachePolicy::off})
      for (std::int64_t budget : budgets) {
        TextureCache cache(budget, policy);
        Model model(budget, policy);
        std::uniform_real_distribution<double> tol_u(0.3, 1.6);
        Tolerances tol{tol_u(rng), tol_u(rng)};
        std::uniform_int_distribution<int> step_u(0, tree.time().steps() - 1);
        std::uniform_int_distribution<int> dir_u(-2, 2);
        int t = 0;
        std::vector<TextureKey> previous;  // textures of the previous frame (budget-free rule)
        TextureKeySet ever;                // since the last drop (budget-free rule, cache on)
        for (int f = 0; f < 40; ++f) {
          const int what = f == 0 ? 0 : int(rng() % 10);
          if (what == 0) {
            t = step_u(rng);  // jump
          } else if (what == 1 && policy == CachePolicy::on) {
            tol = Tolerances{tol_u(rng), tol_u(rng)};  // tolerance edit: drop unreachable
            const TextureKeySet keep = brute_reachable(tree, m, tol);
            cache.drop_unreachable(reachable_textures(tree, m, tol, false));
            model.keep_only(keep);
            ASSERT_EQ(resident_of(cache), model.resident());
            std::erase_if(ever, [&](const TextureKey& k) { return !keep.count(k); });
          } else {
            t = (t + 1) % tree.time().steps();  // playback
          }
          const ViewOrder view = ViewOrder::orthographic(
              {double(dir_u(rng)) + 0.5, double(dir_u(rng)) + 0.25, double(dir_u(rng)) - 0.5});
          const std::vector<Emitted> out =
              traverse({.tree = tree, .step = t, .tol = tol, .errors = m.errors, .view = view});
          const FramePlan plan = plan_frame({.tree = tree,
                                             .step = t,
                                             .emitted = out,
                                             .info = node_info(m),
                                             .tol = tol,
                                             .view = view},
                                            cache);
          const std::vector<TextureKey> drawn = drawn_textures(tree, out, m, tol);
          // Same keys, in the plan's order (which is back-to-front, the brute force's is not).
          std::vector<TextureKey> planned;
          for (const PlannedTexture& p : plan.textures) planned.push_back(p.key);
          ASSERT_EQ(bricks_of(planned), bricks_of(drawn));
          ASSERT_EQ(planned.size(), drawn.size());
          model.begin();
          std::int64_t hits = 0;
          for (const PlannedTexture& p : plan.textures) {
            const bool hit = model.request(p.key, samples_of(tree, p.key.brick) * 2);
            ASSERT_EQ(!p.upload, hit) << "round " << round << " frame " << f;
            hits += hit;
            if (budget == kUnlimited) {
              const bool want = policy == CachePolicy::on
                                    ? ever.count(p.key) != 0
                                    : std::count(previous.begin(), previous.end(), p.key) != 0;
              ASSERT_EQ(hit, want) << "spec rule, round " << round << " frame " << f;
            }
          }
          model.end();
          ASSERT_EQ(resident_of(cache), model.resident()) << "round " << round << " frame " << f;
          ASSERT_EQ(cache.stats().frame_hits, hits);
          ASSERT_EQ(cache.stats().frame_misses, std::int64_t(plan.textures.size()) - hits);
          ASSERT_LE(cache.stats().resident_bytes, budget);
          frames_with_hits += hits > 0;
          frames_with_evictions += !plan.evict_before.empty();
          previous = drawn;
          ever.insert(drawn.begin(), drawn.end());
        }
      }
  }
  // The random cases exercised reuse and in-frame eviction, not just uploads.
  EXPECT_GT(frames_with_hits, 100);
  EXPECT_GT(frames_with_evictions, 20);
}

TEST(TextureCache, TransferFunctionEditInvalidatesNoTexture) {
  std::mt19937 rng(3);
  std::normal_distribution<float> n(5, 2);
  auto s =
      tsptest::MemorySeries::generate({30, 20, 12}, 4, [&](int, int, int, int) { return n(rng); });
  tsptest::MemoryBrickStore store(s, 8);
  const TspTree& tree = store.tree();
  TransferFunction tf = preset_transfer_function("filled", tree.value_range());
  const Tolerances tol{0.05, 0.05};
  const ViewOrder view = ViewOrder::orthographic({0.3, -0.2, 1});
  TextureCache cache(kUnlimited, CachePolicy::on);
  const MetricResult before = compute_errors(Metric::approximate, tree, tf, nullptr, 1);
  const FramePlan first = plan_frame(
      {.tree = tree,
       .step = 2,
       .emitted =
           traverse({.tree = tree, .step = 2, .tol = tol, .errors = before.errors, .view = view}),
       .info = node_info(before),
       .tol = tol,
       .view = view},
      cache);
  ASSERT_GT(first.uploads, 0);
  const auto resident = resident_of(cache);
  // Edit: every entry changes colour and opacity (none becomes fully transparent).
  for (int j = 0; j < tf.size(); ++j) {
    Rgba c = tf.entry(j);
    tf.set_entry(j, Rgba{c.g, c.b, c.r, std::max(0.01f, c.a * 0.5f)});
  }
  const MetricResult after = compute_errors(Metric::approximate, tree, tf, nullptr, 1);
  const FramePlan second = plan_frame(
      {.tree = tree,
       .step = 2,
       .emitted =
           traverse({.tree = tree, .step = 2, .tol = tol, .errors = after.errors, .view = view}),
       .info = node_info(after),
       .tol = tol,
       .view = view},
      cache);
  EXPECT_TRUE(second.evict_before.empty());
  EXPECT_TRUE(second.release_after.empty());
  for (const PlannedTexture& p : second.textures)
    EXPECT_EQ(p.upload, !resident.count({p.key.brick, p.key.t0, p.key.level}));
  for (const auto& k : resident) EXPECT_TRUE(resident_of(cache).count(k));
}

}  // namespace
}  // namespace tsp

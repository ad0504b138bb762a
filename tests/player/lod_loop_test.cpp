// The player's LOD loop (player/lod_loop.h) frame by frame, without a window: interaction holds
// the target frame rate less the frame's overhead, idle refines to full quality after the delay
// and two frames, a pause alone is no change, steady playback follows the speed, and filters,
// the playing rung and LOD off ask for their own cuts; a focus is a change and centres the cut,
// full quality is timed from the last change, the overlay's caption counts the cut by level, and
// a click's focus lies under the click at the volume centre's depth.
#include "player/lod_loop.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>

namespace {

using tspplayer::LodFrameInput;
using tspplayer::LodLoop;
using tspplayer::PlayerState;

PlayerState interactive() {
  PlayerState s;
  s.playing = false;
  s.quality = 0;
  s.lod_on = true;
  s.target_fps = 25;  // 40 ms a frame
  return s;
}

TEST(PlayerLodLoop, IdleRefinesAfterTheDelayAndTwoFramesWithoutAChange) {
  LodLoop loop;
  PlayerState s = interactive();
  const LodFrameInput in;
  tspgl::LodSpec spec = loop.next(s, in, 0.0);  // the first frame: everything is new
  EXPECT_TRUE(loop.changed());
  EXPECT_FALSE(loop.refining());
  EXPECT_EQ(spec.mode, tspgl::LodMode::adaptive);
  EXPECT_DOUBLE_EQ(spec.options.target_ms, 40);
  EXPECT_DOUBLE_EQ(loop.target_ms(), 40);
  loop.next(s, in, 0.1);
  EXPECT_FALSE(loop.changed());
  EXPECT_FALSE(loop.refining());  // one frame, 0.1 s: not yet
  spec = loop.next(s, in, 0.3);
  EXPECT_TRUE(loop.refining());  // two frames and 0.3 s >= kIdleDelaySeconds
  EXPECT_DOUBLE_EQ(spec.options.target_ms, 0);
  EXPECT_DOUBLE_EQ(spec.options.min_error, 0);
  EXPECT_EQ(spec.options.split_limit, tspplayer::kIdleSplitsPerFrame);
  // A change (the view turned) starts over; one slow frame after it is not idle yet.
  s.camera.azimuth_deg += 10;
  loop.next(s, in, 1.0);
  EXPECT_TRUE(loop.changed());
  EXPECT_DOUBLE_EQ(loop.last_change_s(), 1.0);
  loop.next(s, in, 2.0);
  EXPECT_FALSE(loop.refining());
  loop.next(s, in, 2.1);
  EXPECT_TRUE(loop.refining());
  // An edit of the TF or the probes is a change too.
  LodFrameInput edited = in;
  edited.tf_version = 7;
  loop.next(s, edited, 3.0);
  EXPECT_TRUE(loop.changed());
  edited.probe_version = 2;
  loop.next(s, edited, 3.1);
  EXPECT_TRUE(loop.changed());
}

TEST(PlayerLodLoop, APauseAloneIsNoChange) {
  for (const bool keeps : {true, false}) {
    LodLoop loop;
    PlayerState s = interactive();
    LodFrameInput in;
    in.pause_keeps_picture = keeps;
    s.playing = true;
    loop.next(s, in, 0.0);
    loop.next(s, in, 0.1);
    EXPECT_TRUE(loop.changed());  // playing is a change every frame
    s.playing = false;
    loop.next(s, in, 0.2);
    EXPECT_EQ(loop.paused_now(), keeps);
    EXPECT_EQ(loop.changed(), !keeps);
  }
}

TEST(PlayerLodLoop, SteadyPlaybackFollowsTheSpeedAndTheOverheadComesOffTheTarget) {
  LodLoop loop;
  PlayerState s = interactive();
  s.playing = true;
  s.speed = 2;  // 500 ms a step
  const LodFrameInput in;
  EXPECT_DOUBLE_EQ(loop.next(s, in, 0.0).options.target_ms, 40);  // (the first frame: new TF)
  EXPECT_DOUBLE_EQ(loop.next(s, in, 0.5).options.target_ms, 500);
  loop.measured(10, 30);  // 20 ms outside rendering, smoothed by 0.2: 4 ms
  EXPECT_DOUBLE_EQ(loop.overhead_ms(), 4);
  EXPECT_DOUBLE_EQ(loop.next(s, in, 1.0).options.target_ms, 496);
  s.camera.zoom = 2;  // the view moved while playing: the interactive target again
  EXPECT_DOUBLE_EQ(loop.next(s, in, 1.5).options.target_ms, 36);
  // Never below 2 ms of rendering.
  for (int k = 0; k < 100; ++k) loop.measured(0, 1000);
  EXPECT_DOUBLE_EQ(loop.next(s, in, 2.0).options.target_ms, 2);
}

TEST(PlayerLodLoop, FiltersTheRungAndLodOffAskForTheirOwnCuts) {
  PlayerState s = interactive();
  s.splat_fallback = true;
  s.texture_budget_mb = 3;
  LodFrameInput in;
  LodLoop focused;
  focused.focus_on({1, 2, 3}, 0);
  tspgl::LodSpec spec = focused.next(s, in, 0);
  EXPECT_EQ(spec.options.fallback, tsp::LodFallback::splats);
  EXPECT_EQ(spec.options.texture_budget, 3 << 20);
  EXPECT_EQ(spec.options.focus, (std::array<double, 3>{1, 2, 3}));
  s.lod_filter = {tsp::LodFilter::fov, 2};
  spec = LodLoop().next(s, in, 0);
  EXPECT_EQ(spec.mode, tspgl::LodMode::filter);
  EXPECT_EQ(spec.filter, s.lod_filter);
  s.lod_filter = {};
  s.playing = true;
  s.quality = 1;
  in.rung_level = 2;
  spec = LodLoop().next(s, in, 0);
  EXPECT_EQ(spec.mode, tspgl::LodMode::fixed);
  EXPECT_EQ(spec.level, 2);
  in.rung_level = 0;  // a full-resolution rung
  EXPECT_EQ(LodLoop().next(s, in, 0).mode, tspgl::LodMode::off);
  s.lod_on = false;
  LodLoop off;
  EXPECT_EQ(off.next(s, in, 0).mode, tspgl::LodMode::off);
  EXPECT_FALSE(off.refining());
}

TEST(PlayerLodLoop, AFocusIsAChangeAndCentresTheCutUntilCleared) {
  LodLoop loop;
  const PlayerState s = interactive();
  const LodFrameInput in;
  loop.next(s, in, 0.0);
  loop.next(s, in, 0.1);
  EXPECT_TRUE(loop.next(s, in, 0.3).options.focus == std::nullopt);
  EXPECT_TRUE(loop.refining());
  loop.focus_on({4, 5, 6}, 1.0);  // a double-click
  EXPECT_DOUBLE_EQ(loop.last_change_s(), 1.0);
  tspgl::LodSpec spec = loop.next(s, in, 1.1);
  EXPECT_FALSE(loop.refining());  // 0.1 s after the change
  EXPECT_EQ(spec.options.focus, (std::array<double, 3>{4, 5, 6}));
  spec = loop.next(s, in, 1.3);
  EXPECT_TRUE(loop.refining());  // refining keeps the focus
  EXPECT_EQ(spec.options.focus, (std::array<double, 3>{4, 5, 6}));
  loop.clear_focus();  // a new file: no change by itself
  EXPECT_DOUBLE_EQ(loop.last_change_s(), 1.0);
  EXPECT_TRUE(loop.next(s, in, 1.4).options.focus == std::nullopt);
  EXPECT_FALSE(loop.focus());
}

TEST(PlayerLodLoop, FullQualityIsTimedFromTheLastChange) {
  LodLoop loop;
  PlayerState s = interactive();
  const LodFrameInput in;
  tsp::LodFrameStats coarse;
  coarse.cut_size = 9;
  coarse.max_error = 0.5;
  tsp::LodFrameStats full;
  full.cut_size = 64;
  loop.next(s, in, 0.0);
  loop.drawn(full);
  EXPECT_FALSE(loop.cut_full_quality());  // not refining: the cut aimed at a frame time
  loop.note_quality(false, 0.0);
  EXPECT_DOUBLE_EQ(loop.full_quality_after_s(), -1);
  loop.next(s, in, 0.1);
  loop.next(s, in, 0.3);  // refining
  loop.drawn(coarse);
  EXPECT_EQ(loop.stats().cut_size, 9);
  EXPECT_FALSE(loop.cut_full_quality());  // error left
  full.render_scale = 0.5;
  loop.drawn(full);
  EXPECT_FALSE(loop.cut_full_quality());  // not at full size
  full.render_scale = 1;
  loop.drawn(full);
  EXPECT_TRUE(loop.cut_full_quality());
  loop.note_quality(true, 0.75);
  EXPECT_DOUBLE_EQ(loop.full_quality_after_s(), 0.75);
  loop.note_quality(true, 2.0);  // still the first full frame's time
  EXPECT_DOUBLE_EQ(loop.full_quality_after_s(), 0.75);
  s.step = 1;  // a change: timed again from it
  loop.next(s, in, 3.0);
  loop.drawn(std::nullopt);  // no cut drawn: zeros
  EXPECT_EQ(loop.stats().cut_size, 0);
  loop.note_quality(false, 3.0);
  EXPECT_DOUBLE_EQ(loop.full_quality_after_s(), -1);
  loop.note_quality(true, 3.5);
  EXPECT_DOUBLE_EQ(loop.full_quality_after_s(), 0.5);
}

TEST(PlayerLodLoop, TheCutsCaptionCountsItsNodesByLevel) {
  const tsp::Octree o({29, 29, 29}, 8);  // root (level 2), 8 children, 64 leaves
  ASSERT_EQ(o.size(), 73);
  LodLoop loop;
  EXPECT_EQ(tspplayer::cut_text(o, loop.drawn_cut()),
            "LOD cut: 64 nodes, full resolution (level 0)");
  // The first child split into its 8 leaves, the other 7 children drawn whole.
  std::vector<tsp::LodStop> stops(std::size_t(o.size()), tsp::LodStop::none);
  const auto& root = o.node(0);
  for (int k = 0; k < 8; ++k) {
    const int child = root.children[std::size_t(k)];
    if (k > 0) {
      stops[std::size_t(child)] = tsp::LodStop::cut;
      continue;
    }
    for (int leaf : o.node(child).children) stops[std::size_t(leaf)] = tsp::LodStop::splat;
  }
  loop.keep_cut(stops);
  EXPECT_EQ(tspplayer::cut_text(o, loop.drawn_cut()), "LOD cut: 15 nodes, by level 0:8 1:7");
  EXPECT_FALSE(tspplayer::in_cut(o, loop.drawn_cut(), 0));
  EXPECT_TRUE(tspplayer::in_cut(o, loop.drawn_cut(), root.children[1]));
  std::vector<tsp::LodStop> just_root(std::size_t(o.size()), tsp::LodStop::none);
  just_root[0] = tsp::LodStop::cut;
  EXPECT_EQ(tspplayer::cut_text(o, just_root), "LOD cut: 1 node, by level 2:1");
}

TEST(PlayerLodLoop, AClicksFocusLiesUnderTheClickAtTheCentresDepth) {
  const tsp::Dims d{33, 17, 9};
  tsp::CameraParams p;
  p.width = 64;
  p.height = 48;
  const tsp::Camera cam(d, p);
  const glm::dvec3 centre(16, 8, 4);
  const std::array<double, 3> mid = tspplayer::focus_at(cam, d, 32, 24);
  EXPECT_NEAR(mid[0], 16, 1e-9);
  EXPECT_NEAR(mid[1], 8, 1e-9);
  EXPECT_NEAR(mid[2], 4, 1e-9);
  // Off-centre: on the plane through the centre across the view, and projected back onto the
  // clicked pixel.
  const std::array<double, 3> f = tspplayer::focus_at(cam, d, 10, 40);
  const glm::dvec3 q(f[0], f[1], f[2]);
  const auto dir = cam.direction();
  EXPECT_NEAR(glm::dot(q - centre, glm::dvec3(dir[0], dir[1], dir[2])), 0, 1e-9);
  EXPECT_GT(glm::length(q - centre), 1);
  const glm::dvec4 c = cam.view_projection() * glm::dvec4(q, 1);
  EXPECT_NEAR((c.x / c.w * 0.5 + 0.5) * 64, 10, 1e-9);
  EXPECT_NEAR((0.5 - c.y / c.w * 0.5) * 48, 40, 1e-9);
}

}  // namespace

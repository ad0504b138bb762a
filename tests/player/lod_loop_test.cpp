// The player's LOD loop (player/lod_loop.h) frame by frame, without a window: interaction holds
// the target frame rate less the frame's overhead, idle refines to full quality after the delay
// and two frames, a pause alone is no change, steady playback follows the speed, and filters,
// the playing rung and LOD off ask for their own cuts.
#include "player/lod_loop.h"

#include <gtest/gtest.h>

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
  in.focus = std::array<double, 3>{1, 2, 3};
  tspgl::LodSpec spec = LodLoop().next(s, in, 0);
  EXPECT_EQ(spec.options.fallback, tsp::LodFallback::splats);
  EXPECT_EQ(spec.options.texture_budget, 3 << 20);
  EXPECT_EQ(spec.options.focus, in.focus);
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

}  // namespace

// Playing at a quality target: the rung choice against hand-worked ladders (which rung fits the
// period, which keeps the target, which gives when both cannot hold), and the tuner on OSMesa
// against an independent render of each rung's pictures with the renderer itself.
#include "jobs/playback_tuner.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "render/frame_driver.h"
#include "render/volume_renderer.h"
#include "support/paths.h"
#include "tsp/build/build.h"
#include "tsp/metric/lazy_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image_diff.h"
#include "tsp/source/procedural/generate.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {
namespace {

TunedRung rung(const char* name, double de, double ms) { return {{name, 1, 1, 0}, de, de, ms}; }

// full 60 ms, then cheaper rungs with more error.
std::vector<TunedRung> ladder() {
  return {rung("full", 0, 60), rung("a", 0.3, 40), rung("b", 0.7, 30), rung("c", 1.5, 20),
          rung("d", 4, 8)};
}

TEST(PlaybackTuner, EverythingFitsPlaysFullQuality) {
  const RungChoice c = choose_rung(ladder(), 100, 1, 0, 1, true);
  EXPECT_EQ(c.index, 0);
  EXPECT_TRUE(c.fits_rate);
  EXPECT_TRUE(c.within_quality);
  EXPECT_DOUBLE_EQ(c.predicted_ms, 60);
}

TEST(PlaybackTuner, PicksTheLeastErrorThatFitsThePeriodWithinTheTarget) {
  // 41.7 ms (24 steps/s): a (40 ms, dE 0.3) fits; the target 1 × margin 0.9 allows a and b.
  EXPECT_EQ(choose_rung(ladder(), 41.7, 1, 0, 1, true).index, 1);
  // 35 ms: only b (30 ms, 0.7 ≤ 0.9) fits within the target.
  EXPECT_EQ(choose_rung(ladder(), 35, 1, 0, 1, true).index, 2);
  // The window's time: twice the probe's plus 5 ms of UI: a takes 85, b 65, c 45, d 21.
  const RungChoice c = choose_rung(ladder(), 70, 2, 5, 1, true);
  EXPECT_EQ(c.index, 2);
  EXPECT_DOUBLE_EQ(c.predicted_ms, 65);
}

TEST(PlaybackTuner, WhenBothCannotHoldTheUsersChoiceGives) {
  // 25 ms: within the target (a, b) nothing fits; c (20 ms, 1.5) and d fit.
  const RungChoice quality = choose_rung(ladder(), 25, 1, 0, 1, true);
  EXPECT_EQ(quality.index, 2) << "keep quality: the fastest within the target";
  EXPECT_FALSE(quality.fits_rate);
  EXPECT_TRUE(quality.within_quality);
  const RungChoice rate = choose_rung(ladder(), 25, 1, 0, 1, false);
  EXPECT_EQ(rate.index, 3) << "keep rate: the least error that fits";
  EXPECT_TRUE(rate.fits_rate);
  EXPECT_FALSE(rate.within_quality);
  // Nothing fits at all: keep rate takes the fastest.
  EXPECT_EQ(choose_rung(ladder(), 5, 1, 0, 1, false).index, 4);
  EXPECT_EQ(choose_rung(ladder(), 5, 1, 0, 1, true).index, 2);
}

TEST(PlaybackTuner, RungSettingsScaleTheUsersOwn) {
  RenderSettings s;
  s.spacing = 0.75;
  s.render_scale = 0.5;
  const RenderSettings r = rung_settings(s, {"x", 2, 0.7, 1});
  EXPECT_DOUBLE_EQ(r.spacing, 1.5);
  EXPECT_DOUBLE_EQ(r.render_scale, 0.35);
  EXPECT_DOUBLE_EQ(rung_settings(s, {"y", 1, 0.25, 0}).render_scale, kMinRenderScale);
  EXPECT_EQ(playback_rungs().front().spacing_factor, 1);
  EXPECT_EQ(playback_rungs().front().render_scale, 1);
  EXPECT_EQ(playback_rungs().front().lod_level, 0);
}

// The tuner's ΔE for every rung equals the ΔE between the renderer's own pictures of that rung
// and of full quality on the probe steps, drawn here without the tuner (the same driver, LOD
// level and settings); full quality measures 0 and a quarter-size render does not.
TEST(PlaybackTuner, MeasuresEachRungAgainstFullQualityAsTheRendererDrawsIt) {
  auto src = tsp::make_generated_source("shock", {tsp::Dims{33, 30, 28}, 6});
  const std::string path = (tsptest::temp_dir() / "tuner_shock.tsp").string();
  tsp::BuildOptions o;
  o.brick_size = 8;
  tsp::build_tsp_file(*src, path, o);
  auto file = tsp::TspFile::open(path);
  const tsp::TransferFunction tf =
      tsp::preset_transfer_function("filled", file->tree().value_range());
  auto ctx = create_offscreen_context(96, 72);
  tsp::LazyErrors nodes(file->tree(), tsp::Metric::approximate, tf);
  tsp::CameraParams view;
  view.width = 96;
  view.height = 72;
  RenderSettings settings;
  PlaybackTuner tuner(*ctx, *file, tf, nodes, view, settings, 2);
  EXPECT_EQ(tuner.pictures_total(), int(playback_rungs().size()) * 2);
  int rounds = 0;
  while (!tuner.advance(1)) ++rounds;
  EXPECT_GT(rounds, 0) << "a 1 ms budget renders a picture or so per call";
  ASSERT_EQ(tuner.tuned().size(), playback_rungs().size());
  EXPECT_EQ(tuner.tuned()[0].mean_de, 0);
  EXPECT_EQ(tuner.pictures_done(), tuner.pictures_total());

  // The same pictures, drawn directly: steps 1 and 4 (the middles of two halves of 6).
  VolumeRenderer renderer(*ctx, *file, tsp::CachePolicy::off);
  renderer.set_transfer_function(tf);
  const tsp::Camera camera(file->tree().octree().dims(), view);
  auto picture = [&](const Rung& r, int step) {
    LodSpec lod;
    if (r.lod_level > 0) {
      lod.mode = LodMode::fixed;
      lod.level = r.lod_level;
    }
    FrameDriver driver(renderer, lod);
    FrameRequest req;
    req.step = step;
    req.camera = &camera;
    req.settings = rung_settings(settings, r);
    req.metric = &nodes;
    ctx->make_current();
    driver.draw(req);
    return ctx->read_pixels();
  };
  const std::vector<int> steps{1, 4};
  std::vector<tsp::Image> full;
  for (int t : steps) full.push_back(picture(playback_rungs()[0], t));
  double quarter_de = 0;
  for (const TunedRung& t : tuner.tuned()) {
    double mean = 0, worst = 0;
    for (std::size_t i = 0; i < steps.size(); ++i) {
      const double de = tsp::diff_images(picture(t.rung, steps[i]), full[i]).mean;
      mean += de / double(steps.size());
      worst = std::max(worst, de);
    }
    // (A smaller render target magnified into the probe's canvas and into the default
    // framebuffer round a few pixels differently: within 1e-3. At full scale too: refinement's
    // choice of a segment is discrete, and a brick's atlas slot — which differs between the
    // tuner's and these draws — rounds its texture coordinates differently, which can flip it
    // at a pixel or two.)
    EXPECT_NEAR(t.mean_de, mean, 1e-3) << t.rung.name;
    EXPECT_NEAR(t.max_step_de, worst, 1e-3) << t.rung.name;
    EXPECT_GT(t.ms, 0) << t.rung.name;
    if (t.rung.render_scale <= 0.5) quarter_de = std::max(quarter_de, t.mean_de);
  }
  EXPECT_GT(quarter_de, 0.1) << "a half-size picture differs from full quality";
}

}  // namespace
}  // namespace tspgl

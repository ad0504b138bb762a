// Adaptive sampling on OSMesa (tsp/frame/sample_steps.h, RenderSettings::sampling_tol), and the
// caster's exact segments: a textured cube of one colour composites to the exact exponential at
// any spacing and step multiplier (segments cut where the ray enters and leaves), a smooth ramp sampled every 8 voxels stays on the fine
// picture, and a sharp feature keeps its bricks at every spacing.
#include <gtest/gtest.h>

#include <cmath>

#include "render/baseline_renderer.h"
#include "render/volume_renderer.h"
#include "support/function_tsp.h"
#include "support/render_scene.h"
#include "tsp/build/build.h"
#include "tsp/core/color.h"
#include "tsp/frame/sample_steps.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/report/image_diff.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {
namespace {

tsp::TransferFunction tf_of(tsp::Rgba lo, tsp::Rgba hi) {
  const std::vector<tsp::TfPoint> pts = {{0.0, lo}, {1.0, hi}};
  return tsp::TransferFunction::from_points({0, 1}, pts);
}

// One 65³ volume (bricks of 16) and a renderer whose metric is computed under metric_tf — a
// TF under which the nodes vary, so that they are drawn textured whatever the renderer's TF.
struct AdaptiveScene : tsptest::RenderScene {
  AdaptiveScene(const std::string& name, const std::function<float(int, int, int, int)>& f,
                const tsp::TransferFunction& tf, const tsp::TransferFunction& metric_tf)
      : RenderScene(tsptest::build_function_tsp(name, {65, 65, 65}, f), tf, tsp::CachePolicy::on) {
    metric = tsp::compute_errors(tsp::Metric::reference, file->tree(), metric_tf, file.get(), 0);
  }
  // The largest step multiplier (a uniform region takes it at any spacing).
  static double largest_multiplier() { return tsp::kStepMultipliers.back(); }
  tsp::Image frame(const tsp::Camera& cam, double spacing, double sampling_tol, bool dense,
                   FrameReport* report = nullptr, bool all_textured = true) {
    RenderSettings s;
    s.spacing = spacing;
    s.shade = shade;
    s.sampling_tol = sampling_tol;
    s.dense = dense;
    s.reuse_image = false;
    const FrameReport r = renderer->render(0, cam, s, nodes);
    if (all_textured) {
      EXPECT_GT(r.class_percent[std::size_t(tsp::DrawClass::new_texture)] +
                    r.class_percent[std::size_t(tsp::DrawClass::reused_texture)],
                99.9);
    }
    if (report) *report = r;
    return ctx->read_pixels();
  }
  tsp::Image baseline_frame(const tsp::Camera& cam, double spacing) {
    RenderSettings s;
    s.spacing = spacing;
    s.shade = shade;
    baseline->render(0, cam, s);
    return ctx->read_pixels();
  }
};

TEST(AdaptiveSampling, OneColourCubeIsTheExponentialAtAnyStep) {
  // The renderer's TF gives every value one colour, so every cell takes the largest step (8
  // spacings); along +y through the centre the ray crosses 64
  // voxels: α = 1 − (1 − α₁)^64 however the steps fall, the last cut at the ray's end.
  const tsp::Rgba c{0.9f, 0.5f, 0.2f, 0.03f};
  AdaptiveScene scene("adaptive_cube", [](int, int x, int, int) { return float(x) / 64; },
                      tf_of(c, c), tf_of({0, 0, 1, 0.01f}, {1, 0, 0, 0.05f}));
  scene.shade = false;  // the exponential below is the unlit colour
  const double opacity = 1 - std::pow(1 - double(c.a), 64);
  const tsp::Luv want = tsp::srgb_to_luv(c.r * opacity, c.g * opacity, c.b * opacity);
  // Without adaptive sampling too: the caster's segments are cut exactly where the ray enters
  // and leaves, at spacings that do not divide 64 (3, 2.5; samples on the slice planes alone
  // would add or miss up to half a spacing at each end).
  for (bool dense : {true, false}) {
    for (double tol : {0.0, 1.0}) {
      for (double spacing : {1.0, 0.75, 2.5, 3.0}) {
        FrameReport r;
        const tsp::Image img = scene.frame(scene.camera(0, 0), spacing, tol, dense, &r);
        EXPECT_DOUBLE_EQ(r.step_multiplier, tol > 0 ? scene.largest_multiplier() : 1.0);
        EXPECT_EQ(r.dense, dense);
        const std::uint8_t* px = img.at(img.width / 2, img.height / 2);
        EXPECT_LT(tsp::delta_e_luv(tsp::srgb8_to_luv(px[0], px[1], px[2]), want), 1.0)
            << "dense " << dense << ", tol " << tol << ", spacing " << spacing << ": got "
            << int(px[0]) << "," << int(px[1]) << "," << int(px[2]);
      }
    }
  }
}

TEST(AdaptiveSampling, SmoothRampSampledCoarselyStaysOnTheFinePicture) {
  // A slow ramp through a ramp TF: every brick's colour changes little per voxel, so a loose
  // tolerance samples it every 8 voxels, and the picture stays on the baseline's at 0.25.
  const tsp::TransferFunction tf = tf_of({0, 0, 1, 0.01f}, {1, 0.6f, 0, 0.06f});
  AdaptiveScene scene("adaptive_ramp",
                      [](int, int x, int y, int z) { return float(x + y + z) / 192; }, tf, tf);
  const tsp::Camera cam = scene.camera(30, 20);
  const tsp::Image fine = scene.baseline_frame(cam, 0.25);
  for (bool dense : {true, false}) {
    FrameReport r;
    const tsp::Image off = scene.frame(cam, 1.0, 0.0, dense, &r);
    EXPECT_DOUBLE_EQ(r.step_multiplier, 1.0);
    const tsp::Image coarse = scene.frame(cam, 1.0, 0.05, dense, &r);
    EXPECT_DOUBLE_EQ(r.step_multiplier, scene.largest_multiplier()) << "dense " << dense;
    const tsp::DiffStats d_off = tsp::diff_images(off, fine), d = tsp::diff_images(coarse, fine);
    EXPECT_LT(d.mean, 0.5) << "dense " << dense << ": p99 " << d.p99;
    EXPECT_LT(d.p99, 3.0) << "dense " << dense;
    EXPECT_LT(d_off.mean, 0.5) << "dense " << dense;
  }
}

TEST(AdaptiveSampling, SharpFeatureKeepsItsBricksAtEverySpacing) {
  // A thin opaque sheet at x = 40 in an otherwise faint, uniform volume: only the bricks the
  // sheet crosses are sampled every spacing, and the picture stays on the non-adaptive one.
  const tsp::TransferFunction tf = tf_of({0.2f, 0.2f, 1, 0.005f}, {1, 0.3f, 0, 0.6f});
  AdaptiveScene scene(
      "adaptive_sheet",
      [](int, int x, int y, int z) { return std::abs(x - 40) <= 1 ? 1.f : 0.02f * (y + z) / 128; },
      tf, tf);
  const tsp::Camera cam = scene.camera(30, 20);
  for (bool dense : {true, false}) {
    FrameReport r;
    const tsp::Image uniform = scene.frame(cam, 0.5, 0.0, dense, nullptr, false);
    const tsp::Image adaptive = scene.frame(cam, 0.5, 0.02, dense, &r, false);
    // The sheet's bricks at 1, the textured rest coarser.
    EXPECT_GT(r.step_multiplier, 1.5) << "dense " << dense;
    EXPECT_LT(r.step_multiplier, scene.largest_multiplier()) << "dense " << dense;
    const tsp::DiffStats d = tsp::diff_images(adaptive, uniform);
    EXPECT_LT(d.mean, 0.5) << "dense " << dense << ": p99 " << d.p99;
  }
}

TEST(AdaptiveSampling, CellVariationsLeaveWithTheirTextures) {
  const tsp::TransferFunction tf = tf_of({0, 0, 1, 0.01f}, {1, 0.6f, 0, 0.06f});
  AdaptiveScene scene(
      "adaptive_evict", [](int, int x, int y, int z) { return float(x + y + z) / 192; }, tf, tf);
  {
    // BrickTextures keeps a texture's variations until its slot is freed.
    tsp::BrickCache bricks(*scene.file, kDefaultBrickBudget);
    BrickTextures textures(scene.ctx->gl(), bricks);
    int made = 0;
    const auto make = [&] {
      ++made;
      return tsp::CellVariations{};
    };
    const tsp::TextureKey a{0, 0}, b{1, 0};
    textures.upload(a);
    textures.upload(b);
    textures.variations(a, make);
    textures.variations(a, make);
    textures.variations(b, make);
    EXPECT_EQ(made, 2);
    EXPECT_EQ(textures.variations_count(), 2);
    textures.erase(a);
    EXPECT_EQ(textures.variations_count(), 1);
    textures.upload(a);
    textures.variations(a, make);
    EXPECT_EQ(made, 3) << "made again once its texture is back";
    textures.forget_variations();  // a new TF
    EXPECT_EQ(textures.variations_count(), 0);
    EXPECT_EQ(textures.size(), 2);
    textures.variations(b, make);
    textures.clear();
    EXPECT_EQ(textures.variations_count(), 0);
  }
  // Through the renderer: frames that texture every brick under a budget of a few bricks keep
  // the variations of the resident textures only.
  constexpr int kBudgetBricks = 8;
  const tsp::Octree& octree = scene.file->tree().octree();
  const std::int64_t brick_bytes = 2 * octree.max_brick_samples()[0] *
                                   std::int64_t(octree.max_brick_samples()[1]) *
                                   octree.max_brick_samples()[2];
  VolumeRenderer small(*scene.ctx, *scene.file, tsp::CachePolicy::on, kBudgetBricks * brick_bytes);
  small.set_transfer_function(tf);
  RenderSettings s;
  s.sampling_tol = 0.05;
  s.dense = false;
  s.reuse_image = false;
  for (double az : {0.0, 90.0, 200.0}) {
    const FrameReport r = small.render(0, scene.camera(az, 20), s, scene.nodes);
    EXPECT_GT(r.step_multiplier, 1.0);
    EXPECT_LT(small.texture_count(), octree.brick_count());
    EXPECT_GT(small.textures().variations_count(), 0);
    EXPECT_LE(small.textures().variations_count(), small.texture_count()) << "azimuth " << az;
  }
  small.clear_textures();
  EXPECT_EQ(small.textures().variations_count(), 0);
}

}  // namespace
}  // namespace tspgl

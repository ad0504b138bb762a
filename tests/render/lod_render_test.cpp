// LOD levels through the renderer on OSMesa: a constant box at every level against the analytic
// exponential and level 0 (the per-level opacity correction, in every compositing), a linear
// ramp across a boundary between levels without a seam, and splat cuts (flat nodes, no
// textures) of a constant box against the same exponential.
#include <gtest/gtest.h>

#include <cmath>

#include "render/volume_renderer.h"
#include "support/function_tsp.h"
#include "support/render_scene.h"
#include "tsp/build/build.h"
#include "tsp/core/color.h"
#include "tsp/lod/lod_cut.h"
#include "tsp/lod/splat_cut.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {
namespace {

// A .tsp of f, its renderer and a metric that never finds a node coherent, so that every cut
// node is drawn from its brick (a constant field would otherwise be drawn flat, exactly).
struct LodScene : tsptest::RenderScene {
  LodScene(const std::string& name, tsp::Dims d, auto f, const tsp::TransferFunction& tf)
      : RenderScene(tsptest::build_function_tsp(name, d, f), tf, tsp::CachePolicy::on, 160, 120,
                    tsp::Metric::scalar) {
    for (float& e : metric.errors.spatial) e = 1e30f;
  }
  const tsp::Octree& octree() const { return file->tree().octree(); }
  tsp::Image splat_frame(double min_px, double az, double el, Compositing c) {
    const tsp::Camera cam = camera(az, el);
    const tsp::SplatCut cut = tsp::splat_cut(octree(), cam, min_px);
    RenderSettings s;
    s.compositing = c;
    const FrameReport r = renderer->render(0, cam, s, nodes, cut.stops);
    EXPECT_DOUBLE_EQ(r.class_percent[std::size_t(tsp::DrawClass::untextured)], 100.0);
    EXPECT_EQ(r.bytes_uploaded, 0);
    return ctx->read_pixels();
  }
  tsp::Image frame(const tsp::LodCut& cut, double az, double el, Compositing c = Compositing::rays,
                   bool level_tf = true, bool shade = true) {
    RenderSettings s;
    s.compositing = c;
    s.level_tf = level_tf;
    s.shade = shade;
    const FrameReport r = renderer->render(0, camera(az, el), s, nodes, cut.stops());
    EXPECT_DOUBLE_EQ(r.class_percent[std::size_t(tsp::DrawClass::untextured)], 0.0);
    return ctx->read_pixels();
  }
};

tsp::TransferFunction constant_tf(tsp::Rgba c) {
  std::vector<tsp::TfPoint> pts = {{0.0, c}, {1.0, c}};
  return tsp::TransferFunction::from_points({0, 1}, pts);
}

double pixel_delta_e(const tsp::Image& img, const double want[3]) {
  const std::uint8_t* px = img.at(img.width / 2, img.height / 2);
  return tsp::delta_e_luv(tsp::srgb8_to_luv(px[0], px[1], px[2]),
                          tsp::srgb_to_luv(want[0], want[1], want[2]));
}

TEST(LodRender, ConstantBoxAtEveryLevelIsTheExponentialAndLevelZero) {
  // 65³ samples, bricks of 16: 5 bricks per axis, levels 0 … 3. Looking along +y through the
  // centre the ray crosses 64 voxels: α = 1 − (1 − α₁)^64 whatever the level's sample step.
  const tsp::Rgba c{0.9f, 0.5f, 0.2f, 0.03f};
  LodScene scene("lod_cube", {65, 65, 65}, [](int, int, int, int) { return 0.5f; },
                 constant_tf(c));
  ASSERT_EQ(scene.octree().max_lod_level(), 3);
  const double opacity = 1 - std::pow(1 - double(c.a), 64);
  const double want[3] = {c.r * opacity, c.g * opacity, c.b * opacity};
  const tsp::Image level0 = scene.frame(tsp::LodCut::at_level(scene.octree(), 0), 0, 0);
  EXPECT_LT(pixel_delta_e(level0, want), 1.0);
  for (int k = 1; k <= scene.octree().max_lod_level(); ++k) {
    const tsp::LodCut cut = tsp::LodCut::at_level(scene.octree(), k);
    for (Compositing comp : {Compositing::rays, Compositing::boxes, Compositing::slices}) {
      const tsp::Image img = scene.frame(cut, 0, 0, comp);
      EXPECT_LT(pixel_delta_e(img, want), 1.0) << "level " << k << " " << to_string(comp);
      // Obliquely too: the whole picture within 0.5 of level 0's.
      const tsp::Image oblique = scene.frame(cut, 30, 20, comp);
      const tsp::DiffStats d =
          tsp::diff_images(oblique, scene.frame(tsp::LodCut::at_level(scene.octree(), 0), 30, 20));
      EXPECT_LT(d.mean, 0.5) << "level " << k << " " << to_string(comp) << ", p99 " << d.p99;
    }
  }
}

// Mean of channel c over the image, in [0, 1].
double mean_channel(const tsp::Image& img, int c) {
  double sum = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) sum += img.at(x, y)[c];
  return sum / (255.0 * img.width * img.height);
}

// A thin TF band that a fine oscillation crosses everywhere (period 4 voxels on every axis) is
// gone from level 2's data, whose filter averages the oscillation out to about its mean: drawn
// with the TF itself, level 2 shows nothing; with the levels' TF (the TF averaged over the
// level's residual spread, tsp/metric/level_tf.h) it shows the band as a glow giving the light
// level 0's lattice of dots gives (the dots themselves are beyond level 2's resolution, so the
// per-pixel ΔE stays high either way: the test compares the picture's mean colour). The blur is
// weighted by the data's histogram (entry_prior): here the voxel values sit on four spikes
// (0.2, 0.4, 0.6, 0.8, in shares 1:3:3:1) and the band on the top one, so the prior gives the
// band the full eighth of the samples while level 0's trilinear samples cross it only in thin
// shells — the glow is brighter than level 0's light (measured 0.206 against 0.125 unlit; with
// the plain normal blur it was 0.1250), bounded here by twice it.
TEST(LodRender, ThinBandCrossedByAFineOscillationSurvivesLevelTwo) {
  const double kAmp = 0.1;
  const auto wave = [](int i) { return std::sin(M_PI * (i + 0.5) / 2) * M_SQRT2; };  // ±1
  std::vector<tsp::TfPoint> pts = {{0.0, {1, 0.3f, 0.1f, 0}},  {0.77, {1, 0.3f, 0.1f, 0}},
                                   {0.8, {1, 0.3f, 0.1f, 0.5f}}, {0.83, {1, 0.3f, 0.1f, 0}},
                                   {1.0, {1, 0.3f, 0.1f, 0}}};
  const auto tf = tsp::TransferFunction::from_points({0, 1}, pts);
  LodScene scene("lod_thin_band", {65, 65, 65},
                 [&](int x, int y, int z, int) {
                   return float(0.5 + kAmp * (wave(x) + wave(y) + wave(z)));
                 },
                 tf);
  const tsp::LodCut two = tsp::LodCut::at_level(scene.octree(), 2);
  for (bool shade : {false, true}) {
    const tsp::Image level0 =
        scene.frame(tsp::LodCut::at_level(scene.octree(), 0), 30, 20, Compositing::rays, true, shade);
    const double red0 = mean_channel(level0, 0);
    const double with = mean_channel(scene.frame(two, 30, 20, Compositing::rays, true, shade), 0);
    const double without =
        mean_channel(scene.frame(two, 30, 20, Compositing::rays, false, shade), 0);
    ASSERT_GT(red0, 0.02) << "level 0 shows the band";
    EXPECT_LT(without, 0.1 * red0) << "shade " << shade;
    // The band survives as a glow of level 0's light to within a factor of two (lit, level 2's
    // nearly uniform data has almost no gradient and stays unlit: brighter still).
    EXPECT_GT(with, 0.5 * red0) << "shade " << shade;
    EXPECT_LT(with, (shade ? 3.0 : 2.0) * red0) << "shade " << shade;
  }
}

TEST(LodRender, SplatsOfAConstantBoxAreTheExponential) {
  // Each splat is its node's mean colour and opacity composited over the ray's length through
  // its box: on a constant field exact at any cut (the root alone, a middle cut, every leaf), as
  // rays through flat pages and as flat boxes.
  const tsp::Rgba c{0.2f, 0.6f, 0.9f, 0.03f};
  LodScene scene("splat_cube", {65, 65, 65}, [](int, int, int, int) { return 0.5f; },
                 constant_tf(c));
  const double opacity = 1 - std::pow(1 - double(c.a), 64);
  const double want[3] = {c.r * opacity, c.g * opacity, c.b * opacity};
  const tsp::Image level0 = scene.frame(tsp::LodCut::at_level(scene.octree(), 0), 30, 20);
  for (double min_px : {1e9, 20.0, 0.0}) {
    for (Compositing comp : {Compositing::boxes, Compositing::rays}) {
      EXPECT_LT(pixel_delta_e(scene.splat_frame(min_px, 0, 0, comp), want), 1.0)
          << "min " << min_px << " " << to_string(comp);
      const tsp::DiffStats d = tsp::diff_images(scene.splat_frame(min_px, 30, 20, comp), level0);
      EXPECT_LT(d.mean, 0.5) << "min " << min_px << " " << to_string(comp) << ", p99 " << d.p99;
    }
  }
}

TEST(LodRender, LinearRampAcrossALevelBoundaryShowsNoSeam) {
  // v = x / 64 through a TF linear in v: every level reproduces the ramp (the filter is exact on
  // linear fields), so a cut of level-0 bricks for x < 39 and coarser nodes beyond looks like one
  // level.
  std::vector<tsp::TfPoint> pts = {{0.0, {0.1f, 0.2f, 0.9f, 0.01f}}, {1.0, {0.9f, 0.6f, 0.1f, 0.05f}}};
  const auto tf = tsp::TransferFunction::from_points({0, 1}, pts);
  LodScene scene("lod_ramp", {65, 65, 65}, [](int x, int, int, int) { return float(x) / 64; }, tf);
  const tsp::Octree& o = scene.octree();
  tsp::LodCut mixed(o);
  mixed.split(0);
  // Every node of the lower-x children goes down to the leaves; the others keep their levels.
  for (int id = 0; id < o.size(); ++id)
    if (mixed.contains(id) && o.node(id).brick_lo[0] == 0)
      for (std::vector<int> stack{id}; !stack.empty();) {
        const int n = stack.back();
        stack.pop_back();
        if (!mixed.can_split(n)) continue;
        mixed.split(n);
        for (int k : o.node(n).children)
          if (k >= 0) stack.push_back(k);
      }
  ASSERT_TRUE(mixed.covers_once());
  const auto per_level = mixed.nodes_per_level();
  ASSERT_GT(per_level[0], 0);
  ASSERT_GT(per_level[1] + per_level[2], 0);
  const tsp::Image level0 = scene.frame(tsp::LodCut::at_level(o, 0), 30, 20);
  const tsp::Image coarse = scene.frame(tsp::LodCut::at_level(o, 2), 30, 20);
  const tsp::Image img = scene.frame(mixed, 30, 20);
  for (const tsp::Image* single : {&level0, &coarse}) {
    const tsp::DiffStats d = tsp::diff_images(img, *single);
    EXPECT_LT(d.mean, 1.0) << "p99 " << d.p99 << " max " << d.max;
    EXPECT_LT(d.p99, 3.0);
  }
}

}  // namespace
}  // namespace tspgl

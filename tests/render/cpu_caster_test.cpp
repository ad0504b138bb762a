// The CPU ray caster (render/cpu_caster.h) against the GL caster on OSMesa: the same frames —
// lit and unlit, refined and plain, brick grid and whole volume, flat and skipped nodes at a
// tolerance, LOD levels, perspective with the eye inside, the baseline, a stencil — within mean
// ΔE 0.5 and p99 5; the back end each frame reports; what the CPU caster does not draw drawn by
// GL with a note; and the same configuration drawn twice giving the same bytes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "render/baseline_renderer.h"
#include "render/cpu_pass.h"
#include "render/volume_renderer.h"
#include "support/function_scene.h"
#include "support/function_tsp.h"
#include "tsp/lod/lod_cut.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/report/image_diff.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {
namespace {

constexpr double kMaxMean = 0.5, kMaxP99 = 5.0;

// A 65³ field: a ball with a one-voxel jump inside wavy turbulence-like data (bricks of 16).
float field(int x, int y, int z, int) {
  const double r = std::sqrt(double((x - 30) * (x - 30) + (y - 33) * (y - 33) + (z - 31) * (z - 31)));
  const double wave = 0.25 + 0.2 * std::sin(x * 0.31) * std::cos(y * 0.23) * std::sin(z * 0.17 + 1);
  return r < 14.3 ? 1.f : float(std::clamp(wave, 0.0, 0.6));
}

tsp::TransferFunction scene_tf() {
  const std::vector<tsp::TfPoint> pts{{0.0, {0, 0, 0, 0}},          {0.1, {0, 0, 0, 0}},
                                      {0.3, {0.1f, 0.4f, 1, 0.05f}}, {0.45, {1, 0.8f, 0.2f, 0.2f}},
                                      {0.6, {1, 0.2f, 0, 0.02f}},    {0.95, {1, 0.2f, 0, 0.02f}},
                                      {0.98, {1, 1, 1, 0.6f}},       {1.0, {1, 1, 1, 0.6f}}};
  return tsp::TransferFunction::from_points({0, 1}, pts);
}

struct CrossScene : tsptest::FunctionScene {
  CrossScene() : FunctionScene("cpu_cross", field, scene_tf()) {}
  tsp::Camera camera(bool perspective = false, bool eye_inside = false) const {
    tsp::CameraParams p;
    p.projection = perspective ? tsp::Projection::perspective : tsp::Projection::orthographic;
    if (eye_inside) p.eye = std::array<double, 3>{40, 20, 36};
    return FunctionScene::camera(p);
  }
  FrameReport last;
  tsp::Image frame(RenderSettings s, Backend b, const tsp::Camera& cam, const tsp::LodCut* cut = nullptr) {
    s.backend = b;
    s.reuse_image = false;
    last = renderer->render(0, cam, s, nodes, cut ? cut->stops() : tsp::LodStops{});
    return ctx->read_pixels();
  }
  tsp::Image base_frame(RenderSettings s, Backend b) {
    s.backend = b;
    last = baseline->render(0, camera(), s);
    EXPECT_EQ(last.backend, b == Backend::cpu ? "cpu" : "gl");
    return ctx->read_pixels();
  }
};

CrossScene& scene() {
  static CrossScene* s = new CrossScene();
  return *s;
}

void expect_match(const std::string& what, const tsp::Image& cpu, const tsp::Image& gl) {
  const tsp::DiffStats d = tsp::diff_images(cpu, gl);
  std::printf("%-40s mean %.3f p99 %.3f max %.1f\n", what.c_str(), d.mean, d.p99, d.max);
  EXPECT_LT(d.mean, kMaxMean) << what;
  EXPECT_LT(d.p99, kMaxP99) << what;
}

// Calls f(settings, name) for lit and unlit, plain and refined, the whole volume as one page
// and bricks (bricks alone without both_layouts), at tolerance 0 and 0.05.
void for_each_setting(bool both_layouts,
                      const std::function<void(const RenderSettings&, const std::string&)>& f) {
  for (bool shade : {false, true})
    for (double refine : {0.0, 0.3})
      for (bool dense : {true, false})
        for (double tol : {0.0, 0.05}) {
          if (dense && !both_layouts) continue;
          RenderSettings s;
          s.shade = shade;
          s.refine_tol = refine;
          s.dense = dense;
          s.tol = {tol, 0};
          char what[96];
          std::snprintf(what, sizeof what, "%s refine %.1f %s tol %.2f", shade ? "lit" : "unlit",
                        refine, dense ? "dense" : "bricks", tol);
          f(s, what);
        }
}

TEST(CpuCaster, MatchesTheGlCasterOnEveryConfiguration) {
  CrossScene& sc = scene();
  for_each_setting(true, [&](const RenderSettings& s, const std::string& what) {
    const tsp::Image cpu = sc.frame(s, Backend::cpu, sc.camera());
    EXPECT_EQ(sc.last.backend, "cpu") << what;
    EXPECT_TRUE(sc.last.backend_note.empty()) << what;
    const tsp::Image gl = sc.frame(s, Backend::gl, sc.camera());
    EXPECT_EQ(sc.last.backend, "gl") << what;
    expect_match(what, cpu, gl);
  });
}

TEST(CpuCaster, MatchesOnLodLevelsPerspectiveAndTheBaseline) {
  CrossScene& sc = scene();
  for (int level : {1, 2}) {
    const tsp::LodCut cut = tsp::LodCut::at_level(sc.file->tree().octree(), level);
    for (bool level_tf : {false, true}) {
      RenderSettings s;
      s.level_tf = level_tf;
      expect_match("level " + std::to_string(level) + (level_tf ? " level-tf" : ""),
                   sc.frame(s, Backend::cpu, sc.camera(), &cut),
                   sc.frame(s, Backend::gl, sc.camera(), &cut));
    }
  }
  RenderSettings s;
  expect_match("perspective", sc.frame(s, Backend::cpu, sc.camera(true)),
               sc.frame(s, Backend::gl, sc.camera(true)));
  expect_match("perspective, eye inside", sc.frame(s, Backend::cpu, sc.camera(true, true)),
               sc.frame(s, Backend::gl, sc.camera(true, true)));
  for (bool shade : {false, true}) {
    s.shade = shade;
    s.spacing = 1;
    expect_match(std::string("baseline ") + (shade ? "lit" : "unlit"), sc.base_frame(s, Backend::cpu),
                 sc.base_frame(s, Backend::gl));
  }
}

TEST(CpuCaster, WhatItCannotDrawIsDrawnByGlWithANote) {
  CrossScene& sc = scene();
  RenderSettings s;
  s.preintegrated = true;
  const tsp::Image cpu = sc.frame(s, Backend::cpu, sc.camera());
  EXPECT_EQ(sc.last.backend, "gl");
  EXPECT_NE(sc.last.backend_note.find("pre-integration"), std::string::npos) << sc.last.backend_note;
  EXPECT_EQ(tsp::diff_images(cpu, sc.frame(s, Backend::gl, sc.camera())).max, 0.0);
  s.preintegrated = false;
  s.compositing = Compositing::slices;
  sc.frame(s, Backend::cpu, sc.camera());
  EXPECT_EQ(sc.last.backend, "gl");
  EXPECT_NE(sc.last.backend_note.find("slices"), std::string::npos) << sc.last.backend_note;
  // GL asked for: no note.
  sc.frame(s, Backend::gl, sc.camera());
  EXPECT_TRUE(sc.last.backend_note.empty());
}

TEST(CpuCaster, AutoCastsOnTheCpuWhereGlIsSoftware) {
  EXPECT_TRUE(software_renderer("llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5"));
  EXPECT_TRUE(software_renderer("Mesa OffScreen softpipe"));
  EXPECT_FALSE(software_renderer("NVIDIA H100 PCIe/PCIe/SSE2, OpenGL 4.6"));
  CrossScene& sc = scene();
  RenderSettings s;
  sc.frame(s, Backend::automatic, sc.camera());
  EXPECT_EQ(sc.last.backend, software_renderer(sc.ctx->describe()) ? "cpu" : "gl")
      << sc.ctx->describe();
}

TEST(CpuCaster, TheSameFrameIsTheSameBytesWhereverItsBricksSit) {
  // A second renderer that drew other frames first holds the bricks in other atlas slots: the
  // CPU caster's weights come from the sample grid alone, so its pictures are equal.
  CrossScene& sc = scene();
  VolumeRenderer other(*sc.ctx, *sc.file, tsp::CachePolicy::on);
  other.set_transfer_function(scene_tf());
  RenderSettings s;
  s.backend = Backend::cpu;
  s.reuse_image = false;
  s.tol = {0.3, 0};
  other.render(0, sc.camera(true), s, sc.nodes);
  const tsp::LodCut cut = tsp::LodCut::at_level(sc.file->tree().octree(), 1);
  other.render(0, sc.camera(), s, sc.nodes, cut.stops());
  s.tol = {0, 0.1};
  for (bool dense : {false, true}) {
    s.dense = dense;
    other.render(0, sc.camera(), s, sc.nodes);
    const tsp::Image a = sc.ctx->read_pixels();
    const tsp::Image b = sc.frame(s, Backend::cpu, sc.camera());
    EXPECT_EQ(a.rgba, b.rgba) << "dense " << dense;
  }
}

TEST(CpuCaster, SwitchingCastersRedrawsTheWholePicture) {
  // Partial-image reuse keeps pixels only when nothing changed: a frame cast by the other back
  // end is drawn whole, so the picture is that caster's (a paused player switching --backend).
  CrossScene& sc = scene();
  RenderSettings s;
  s.reuse_image = true;
  for (Backend first : {Backend::cpu, Backend::gl}) {
    const Backend second = first == Backend::cpu ? Backend::gl : Backend::cpu;
    s.backend = first;
    sc.renderer->render(0, sc.camera(), s, sc.nodes);
    s.backend = second;
    const FrameReport r = sc.renderer->render(0, sc.camera(), s, sc.nodes);
    EXPECT_EQ(r.redrawn_percent, 100) << to_string(second);
    EXPECT_EQ(r.backend, to_string(second));
    const tsp::Image switched = sc.ctx->read_pixels();
    EXPECT_EQ(switched.rgba, sc.frame(s, second, sc.camera()).rgba) << to_string(second);
  }
}

TEST(CpuCaster, RunsOfTheDenseRegionDrawWhatBrickByBrickDraws) {
  // The CPU caster walks runs of full-resolution bricks as one volume in the dense region; the
  // samples and their lighting are the brick-by-brick walk's (up to rounding: SIMD lanes where
  // the brick-by-brick walk went one by one across faces).
  CrossScene& sc = scene();
  for_each_setting(false, [&](const RenderSettings& s, const std::string& what) {
    sc.renderer->set_dense_host(false);
    const tsp::Image bricks = sc.frame(s, Backend::cpu, sc.camera());
    sc.renderer->set_dense_host(true);
    const tsp::Image runs = sc.frame(s, Backend::cpu, sc.camera());
    const tsp::DiffStats d = tsp::diff_images(runs, bricks);
    std::printf("runs against bricks, %-28s mean %.4f p99 %.3f max %.1f\n", what.c_str(), d.mean,
                d.p99, d.max);
    EXPECT_LT(d.mean, 0.01) << what;
    EXPECT_LT(d.p99, 0.2) << what;
  });
}

TEST(CpuCaster, TheDenseRegionHoldsTheSameTexelsWhateverStepCameBefore) {
  // Two steps: the low bricks along x change much (a key per step), the others drift within
  // the temporal tolerance (one key for both steps). The texels a changed brick shares with a
  // higher unchanged one must be the higher one's whatever the frames drawn before (a fresh
  // renderer draws the same bytes).
  auto f = [](int x, int y, int z, int t) {
    return std::min(field(x, y, z, 0) * (x < 24 && t == 1 ? 0.6f : 1.f) + 0.004f * float(t), 1.f);
  };
  const std::string path = tsptest::build_function_tsp("cpu_dense_steps", {65, 65, 65}, f, 16, 2);
  CrossScene& sc = scene();
  auto file = tsp::TspFile::open(path);
  const tsp::MetricResult m =
      tsp::compute_errors(tsp::Metric::reference, file->tree(), scene_tf(), file.get(), 0);
  tsp::WholeTreeMetric nodes(m);
  RenderSettings s;
  s.backend = Backend::cpu;
  s.reuse_image = false;
  s.dense = false;
  s.tol = {0, 0.1};
  auto draw = [&](VolumeRenderer& r, int step) {
    const FrameReport rep = r.render(step, sc.camera(), s, nodes);
    EXPECT_EQ(rep.backend, "cpu");
    return sc.ctx->read_pixels();
  };
  for (int step : {0, 1}) {
    VolumeRenderer after(*sc.ctx, *file, tsp::CachePolicy::on);
    after.set_transfer_function(scene_tf());
    // (The atlas grows in the second frame, which places every brick again: the third frame
    // places only the bricks whose key changed.)
    draw(after, step);
    draw(after, 1 - step);
    const tsp::Image a = draw(after, step);
    VolumeRenderer fresh(*sc.ctx, *file, tsp::CachePolicy::on);
    fresh.set_transfer_function(scene_tf());
    EXPECT_EQ(a.rgba, draw(fresh, step).rgba) << "step " << step;
  }
}

TEST(CpuCaster, BricksDrawnFromTwoStepsShareTheirFacesOnBothBackEnds) {
  // Two steps: only the voxels from x = 26 up change (much), the layer x = 26 included, which
  // the bricks below store as their upper shared layer (65 samples in 5 bricks of 13 cells). The bricks below stay coherent (one
  // texture for both steps), so at a step they are drawn from another step's texture than the
  // brick above. The shared texels must be the brick above's on the GL caster, the CPU caster's
  // runs and its brick-by-brick walk alike (BrickTextures::stitch): without it the GL caster and
  // the walk read the lower brick's copy of the layer, the runs the upper brick's.
  constexpr int kFace = 26;
  auto f = [](int x, int y, int z, int t) {
    return field(x, y, z, 0) * (x >= kFace && t == 1 ? 0.55f : 1.f);
  };
  const std::string path = tsptest::build_function_tsp("cpu_stitch_steps", {65, 65, 65}, f, 16, 2);
  CrossScene& sc = scene();
  auto file = tsp::TspFile::open(path);
  ASSERT_EQ(file->tree().octree().lattice(2).origin[0], kFace);
  const tsp::MetricResult m =
      tsp::compute_errors(tsp::Metric::reference, file->tree(), scene_tf(), file.get(), 0);
  tsp::WholeTreeMetric nodes(m);
  RenderSettings s;
  s.reuse_image = false;
  s.dense = false;
  s.tol = {0, 0.1};
  for (int step : {0, 1}) {
    auto draw = [&](Backend b, bool runs) {
      VolumeRenderer r(*sc.ctx, *file, tsp::CachePolicy::on);
      r.set_transfer_function(scene_tf());
      r.set_dense_host(runs);
      s.backend = b;
      r.render(1 - step, sc.camera(), s, nodes);  // the other step first: slots already held
      const FrameReport rep = r.render(step, sc.camera(), s, nodes);
      EXPECT_EQ(rep.backend, b == Backend::cpu ? "cpu" : "gl");
      return sc.ctx->read_pixels();
    };
    const tsp::Image gl = draw(Backend::gl, false), runs = draw(Backend::cpu, true),
                     bricks = draw(Backend::cpu, false);
    for (const auto& [what, img] : {std::pair{"runs", &runs}, std::pair{"bricks", &bricks}}) {
      const tsp::DiffStats d = tsp::diff_images(*img, gl);
      std::printf("step %d, GL against the CPU caster's %s: mean %.4f p99 %.3f max %.1f\n", step,
                  what, d.mean, d.p99, d.max);
      EXPECT_LT(d.mean, 0.02) << what << ", step " << step;
      EXPECT_LT(d.p99, 0.5) << what << ", step " << step;
    }
  }
}

TEST(CpuCaster, TheSameFrameTwiceIsTheSameBytes) {
  CrossScene& sc = scene();
  for (Backend b : {Backend::cpu, Backend::gl}) {
    RenderSettings s;
    s.tol = {0.05, 0};
    const tsp::Image a = sc.frame(s, b, sc.camera());
    const tsp::Image c = sc.frame(s, b, sc.camera());
    EXPECT_EQ(a.rgba, c.rgba) << to_string(b);
  }
}

}  // namespace
}  // namespace tspgl

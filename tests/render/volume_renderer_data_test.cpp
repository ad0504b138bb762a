// The renderer on OSMesa on generated and real data: partial-image reuse against redrawing, the
// compositing methods on CFD, zero-tolerance TSP frames against the non-TSP baseline, the dense
// volume against the brick grid, cache on/off, tolerance changes, class shares against the
// traversal, lazy errors across a TF edit, uploads and budgets, an in-memory brick store.
// Failing image comparisons write actual, expected and difference PNGs under test-output/.
#include "render/volume_renderer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <tuple>

#include "support/memory_source.h"
#include "render/baseline_renderer.h"
#include "support/memory_tree.h"
#include "support/paths.h"
#include "support/render_scene.h"
#include "tsp/build/build.h"
#include "tsp/core/color.h"
#include "tsp/core/error.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/lazy_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"
#include "tsp/source/open_source.h"
#include "tsp/source/procedural/generate.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {
namespace {

namespace fs = std::filesystem;

using namespace tsptest;  // the render scene, build_tsp and the image checks

// Partial-image reuse is exact: playing a series with a temporal tolerance (long spans, so most
// bricks are drawn as in the previous frame) gives the same pixels as redrawing everything, for
// every compositing, unlit and lit, while redrawing only part of the image; a view change redraws
// it all. Lit slices are exact to one 8-bit level: a slice polygon cut to a redrawn rectangle
// interpolates its texture coordinates with other rounding, and a lit sample's normal from the
// differences of a nearly uniform region turns with it (unlit, the same rounding changes nothing).
TEST(VolumeRenderer, PartialImageReuseGivesTheSamePixelsAsRedrawing) {
  const fs::path h5 = tsptest::datasets_dir() / "samples" / "hotPlume_32.h5";
  tsp::SourceOptions so;
  so.field = "T";
  auto src = tsp::open_source(h5.string(), so);
  const std::string path = build_tsp(*src, "plume_reuse", {}, 8);
  auto file = tsp::TspFile::open(path);
  const auto tf = tsp::preset_transfer_function("filled", file->tree().value_range());
  RenderScene with(path, tf, tsp::CachePolicy::on), without(path, tf, tsp::CachePolicy::on);
  for (bool shade : {false, true})
    for (Compositing comp : {Compositing::slices, Compositing::boxes, Compositing::rays}) {
      double redrawn = 0;
      int frames = 0;
      for (int pass = 0; pass < 2; ++pass) {
        const tsp::Camera cam = with.camera(35 + 40 * pass, 15);
        for (int step = 20; step <= 30; ++step) {
          RenderSettings s;
          s.compositing = comp;
          s.tol = {0, 0.01};
          s.shade = shade;
          s.reuse_image = true;
          const FrameReport r = with.renderer->render(step, cam, s, with.nodes);
          const tsp::Image a = with.ctx->read_pixels();
          s.reuse_image = false;
          without.renderer->render(step, cam, s, without.nodes);
          const tsp::Image b = without.ctx->read_pixels();
          const std::string what = std::string(to_string(comp)) + (shade ? " lit" : " unlit") +
                                   " step " + std::to_string(step) + " pass " +
                                   std::to_string(pass);
          if (shade && comp == Compositing::slices)
            ASSERT_LT(tsp::diff_images(a, b).max, 0.5) << what << keep_failure("reuse", a, b);
          else
            ASSERT_EQ(a.rgba, b.rgba) << what
                                      << (a.rgba == b.rgba ? "" : keep_failure("reuse", a, b));
          if (step == 20) {
            EXPECT_DOUBLE_EQ(r.redrawn_percent, 100.0) << "a new view redraws all";
          }
          redrawn += r.redrawn_percent;
          ++frames;
        }
      }
      EXPECT_LT(redrawn / frames, 60.0) << to_string(comp) << ": reuse kept most of the image";
    }
}

// The three ways of compositing textured boxes take the same samples: per-brick rays and the
// one-pass ray caster agree with slices, for the TSP renderer and the baseline, on real CFD data.
TEST(VolumeRenderer, CompositingMethodsAgreeOnRealCfd) {
  const fs::path h5 = tsptest::datasets_dir() / "samples" / "hotPlume_32.h5";
  tsp::SourceOptions so;
  so.field = "T";
  auto src = tsp::open_source(h5.string(), so);
  const std::string path = build_tsp(*src, "plume_methods", {}, 8);
  auto file = tsp::TspFile::open(path);
  for (const char* preset : {"sparse", "filled"}) {
    RenderScene scene(path, tsp::preset_transfer_function(preset, file->tree().value_range()),
                      tsp::CachePolicy::on);
    for (bool perspective : {false, true}) {
      const tsp::Camera cam = scene.camera(35, 15, perspective);
      // (Refinement, on by default for rays, samples differently where the TF bends: off where
      // rays must take the slices' samples, on where they are compared with the fine picture.)
      auto frame = [&](Compositing comp, bool baseline, double spacing = 0.7,
                       double refine_tol = 0) {
        RenderSettings s;
        s.compositing = comp;
        s.spacing = spacing;
        s.refine_tol = refine_tol;
        if (baseline)
          scene.baseline->render(30, cam, s);
        else
          scene.renderer->render(30, cam, s, scene.nodes);
        return scene.ctx->read_pixels();
      };
      const tsp::Image tsp_ref = frame(Compositing::slices, false);
      const tsp::Image base_ref = frame(Compositing::slices, true);
      const std::string name = std::string("methods_") + preset + (perspective ? "_persp" : "");
      // Boxes sample the slices' planes: only silhouette pixels may differ (the volume's edge
      // rasterised as slice polygons or as box faces).
      expect_close(name + "_tsp_boxes", frame(Compositing::boxes, false), tsp_ref, 0.1, 1.0);
      expect_close(name + "_baseline_boxes", frame(Compositing::boxes, true), base_ref, 0.1, 1.0);
      // Rays cut the planes' segments exactly where the ray enters and leaves the volume (the
      // slices miss or add up to half a spacing there): close to the slices, and closer than
      // they are to the fine picture (slices at a quarter of the spacing).
      const tsp::Image fine = frame(Compositing::slices, true, 0.7 / 4);
      for (bool baseline : {false, true}) {
        const tsp::Image rays = frame(Compositing::rays, baseline);
        const tsp::Image& slices = baseline ? base_ref : tsp_ref;
        const std::string what = name + (baseline ? "_baseline" : "_tsp") + "_rays";
        expect_close(what, rays, slices, 0.5, 4.0);
        const double rays_error =
            tsp::diff_images(frame(Compositing::rays, baseline, 0.7, tsp::kDefaultRefineTol), fine)
                .mean;
        const double slices_error = tsp::diff_images(slices, fine).mean;
        EXPECT_LE(rays_error, slices_error + 0.02) << what << ": rays " << rays_error
                                                   << ", slices " << slices_error;
      }
    }
  }
}

TEST(VolumeRenderer, ZeroToleranceMatchesBaselineOnGeneratedData) {
  auto src = tsp::make_generated_source("shock", {tsp::Dims{40, 36, 30}, 6});
  const std::string path = build_tsp(*src, "shock");
  auto file = tsp::TspFile::open(path);
  for (const char* preset : {"sparse", "filled"}) {
    RenderScene scene(path, tsp::preset_transfer_function(preset, file->tree().value_range()),
                      tsp::CachePolicy::on);
    for (int step : {0, 3, 5}) {
      for (auto [az, el, persp] : {std::tuple{30.0, 20.0, false}, std::tuple{-120.0, 55.0, false},
                                   std::tuple{70.0, -25.0, true}}) {
        const tsp::Camera cam = scene.camera(az, el, persp);
        expect_close(std::string("shock_") + preset + "_" + std::to_string(step) +
                         (persp ? "_perspective" : ""),
                     scene.tsp_frame(step, cam), scene.baseline_frame(step, cam), 0.5, 3.0);
      }
    }
  }
}

// A frame that textures every leaf brick (a filled TF over data with nothing transparent or
// uniform) is ray cast through one whole-volume texture: the same picture as the brick grid's
// walk, at zero tolerance and with a temporal tolerance that shows bricks of several steps
// (their shared layers differ: within 0.1 mean ΔE); frames with transparent bricks walk the
// grid.
TEST(VolumeRenderer, DenseWholeVolumeRaysMatchTheBrickGrid) {
  auto src = tsptest::MemorySource::from_function({40, 36, 30}, 6, [](int x, int y, int z, int t) {
    return float(std::sin(0.31 * x + 0.1 * t) * std::cos(0.23 * y) + 0.05 * z + 0.3 * t);
  });
  const std::string path = build_tsp(src, "dense");
  auto file = tsp::TspFile::open(path);
  RenderScene scene(path, tsp::preset_transfer_function("filled", file->tree().value_range()),
                    tsp::CachePolicy::on);
  auto frame = [&](int step, bool dense, tsp::Tolerances tol, bool& used) {
    RenderSettings s;
    s.dense = dense;
    s.tol = tol;
    s.reuse_image = false;
    const FrameReport r = scene.renderer->render(step, scene.camera(30, 20), s, scene.nodes);
    used = r.dense;
    return scene.ctx->read_pixels();
  };
  bool used = false, grid_used = true;
  for (int step : {0, 4}) {
    const tsp::Image dense = frame(step, true, {}, used);
    EXPECT_TRUE(used) << step;
    const tsp::Image grid = frame(step, false, {}, grid_used);
    EXPECT_FALSE(grid_used);
    expect_close("dense_" + std::to_string(step), dense, grid, 0.01, 0.1);
  }
  // Spans merged in time: bricks of several steps side by side.
  const tsp::Tolerances merged{0, 10};
  const tsp::Image dense = frame(3, true, merged, used);
  EXPECT_TRUE(used);
  expect_close("dense_merged", dense, frame(3, false, merged, grid_used), 0.1, 2.0);
  // Transparent bricks (the sparse TF): the grid walk, which leaps over them.
  RenderScene sparse(path, tsp::preset_transfer_function("sparse", file->tree().value_range()),
                     tsp::CachePolicy::on);
  RenderSettings s;
  EXPECT_FALSE(sparse.renderer->render(0, sparse.camera(30, 20), s, sparse.nodes).dense);
}

TEST(VolumeRenderer, ZeroToleranceMatchesBaselineOnRealData) {
  const fs::path nc = katrina_file();
  if (!fs::exists(nc)) GTEST_SKIP() << nc << " not present";
  tsp::SourceOptions so;
  so.field = "QCLOUD";
  auto src = tsp::open_source(nc.string(), so);
  const std::string path = build_tsp(*src, "katrina");
  auto file = tsp::TspFile::open(path);
  RenderScene scene(path, tsp::preset_transfer_function("filled", file->tree().value_range()),
                    tsp::CachePolicy::on);
  for (int step = 0; step < 4; ++step) {
    const tsp::Camera cam = scene.camera(20, 35);
    expect_close("katrina_" + std::to_string(step), scene.tsp_frame(step, cam),
                 scene.baseline_frame(step, cam), 0.5, 3.0);
  }
}

TEST(VolumeRenderer, ZeroToleranceMatchesBaselineOnRealCfd) {
  // Two buoyant plumes from OpenFOAM (datasets/README.md), 32³ × 41 steps.
  const fs::path h5 = tsptest::datasets_dir() / "samples" / "hotPlume_32.h5";
  tsp::SourceOptions so;
  so.field = "T";
  auto src = tsp::open_source(h5.string(), so);
  const std::string path = build_tsp(*src, "plume");
  auto file = tsp::TspFile::open(path);
  for (const char* preset : {"sparse", "filled"}) {
    RenderScene scene(path, tsp::preset_transfer_function(preset, file->tree().value_range()),
                      tsp::CachePolicy::on);
    for (int step : {5, 25, 40}) {
      const tsp::Camera cam = scene.camera(35, 15);
      expect_close(std::string("plume_") + preset + "_" + std::to_string(step),
                   scene.tsp_frame(step, cam), scene.baseline_frame(step, cam), 0.5, 3.0);
    }
  }
}

TEST(VolumeRenderer, CacheOnAndOffGiveTheSamePicture) {
  auto src = tsp::make_generated_source("shock", {tsp::Dims{33, 30, 28}, 8});
  const std::string path = build_tsp(*src, "shock", {}, 8);
  auto file = tsp::TspFile::open(path);
  const auto tf = tsp::preset_transfer_function("filled", file->tree().value_range());
  RenderScene on(path, tf, tsp::CachePolicy::on), off(path, tf, tsp::CachePolicy::off);
  const tsp::Camera cam = on.camera();
  // A temporal tolerance makes spans longer than one step, so textures are reused (RT).
  for (tsp::Tolerances tol : {tsp::Tolerances{0, 0}, tsp::Tolerances{0, 0.05}}) {
    for (int step : {0, 1, 2, 3, 7, 6, 0, 4}) {
      // The same bricks, sampled from different atlas slots: equal up to texel-weight rounding.
      tsp::Image a = on.tsp_frame(step, cam, tol), b = off.tsp_frame(step, cam, tol);
      const tsp::DiffStats d = tsp::diff_images(a, b);
      EXPECT_TRUE(d.mean < 0.01 && d.max < 1.0)
          << "step " << step << " temporal tol " << tol.temporal << ": mean " << d.mean << " max "
          << d.max << " " << (d.max < 1.0 ? "" : keep_failure("cache_" + std::to_string(step), a, b));
    }
  }
}

TEST(VolumeRenderer, ToleranceChangeDropsUnreachableTexturesAndKeepsThePicture) {
  auto src = tsp::make_generated_source("shock", {tsp::Dims{33, 30, 28}, 6});
  const std::string path = build_tsp(*src, "shock", {}, 8);
  auto file = tsp::TspFile::open(path);
  RenderScene scene(path, tsp::preset_transfer_function("filled", file->tree().value_range()),
                    tsp::CachePolicy::on, 80, 60, tsp::Metric::approximate);
  // Unlit: lit, the faces beside transparent and flat bricks take one-sided differences where
  // the baseline's are central, p99 4 against the bound of 3 (docs/rendering.md, lighting).
  scene.shade = false;
  const tsp::Camera cam = scene.camera();
  for (int step = 0; step < 6; ++step) scene.tsp_frame(step, cam);
  const int before = scene.renderer->texture_count();
  ASSERT_GT(before, 0);
  // A spatial tolerance above every e_s draws everything flat: no texture stays reachable.
  float max_es = 0;
  for (float e : scene.metric.errors.spatial) max_es = std::max(max_es, e);
  const tsp::Tolerances loose{double(max_es) + 1, 1e9};
  EXPECT_EQ(scene.renderer->drop_unreachable(scene.nodes, loose, true), before);
  EXPECT_EQ(scene.renderer->texture_count(), 0);
  // Back at zero tolerance nothing is reachable-but-missing: frames render as before.
  EXPECT_EQ(scene.renderer->drop_unreachable(scene.nodes, {}, true), 0);
  tsp::Image again = scene.tsp_frame(3, cam);
  expect_close("tolerance_round_trip", again, scene.baseline_frame(3, cam), 0.5, 3.0);
}

TEST(VolumeRenderer, ClassSharesSumTo100AndMatchTheTraversal) {
  auto src = tsp::make_generated_source("shock", {tsp::Dims{33, 33, 33}, 8});
  const std::string path = build_tsp(*src, "shock", {}, 8);
  auto file = tsp::TspFile::open(path);
  RenderScene scene(path, tsp::preset_transfer_function("sparse", file->tree().value_range()),
                    tsp::CachePolicy::on, 64, 48, tsp::Metric::approximate);
  const tsp::Camera cam = scene.camera();
  const tsp::TspTree& tree = file->tree();
  for (tsp::Tolerances tol : {tsp::Tolerances{0, 0}, tsp::Tolerances{0.3, 0.2}}) {
    for (int step = 0; step < 8; ++step) {
      RenderSettings s;
      s.tol = tol;
      FrameReport r = scene.renderer->render(step, cam, s, scene.nodes);
      double sum = 0;
      for (double p : r.class_percent) sum += p;
      EXPECT_NEAR(sum, 100.0, 1e-9);
      // NR and UP from the traversal's own output, counted independently.
      auto emitted = tsp::traverse({.tree = tree,
                                    .step = step,
                                    .tol = tol,
                                    .errors = scene.metric.errors,
                                    .view = tsp::ViewOrder::orthographic(cam.direction())});
      double nr = 0, up = 0, total = double(tree.octree().dims().count());
      for (const auto& e : emitted) {
        const int id = tree.id(e.octree_id, e.time_id);
        const double v = double(tree.octree().node(e.octree_id).box.count());
        if (scene.metric.transparent[std::size_t(id)]) nr += v;
        else if (scene.metric.errors.spatial[std::size_t(id)] <= tol.spatial) up += v;
      }
      EXPECT_NEAR(r.class_percent[0], 100 * nr / total, 1e-9) << "step " << step;
      EXPECT_NEAR(r.class_percent[1], 100 * up / total, 1e-9) << "step " << step;
    }
  }
}

// The live-metric overload draws exactly what the whole-tree metric draws, also after a TF edit
// (which LazyErrors notices through the TF's version) and at non-zero tolerances.
TEST(VolumeRenderer, LazyErrorsRenderLikeTheWholeTreeMetricAcrossATfEdit) {
  auto src = tsp::make_generated_source("shock", {tsp::Dims{33, 30, 28}, 6});
  const std::string path = build_tsp(*src, "shock", {}, 8);
  auto file = tsp::TspFile::open(path);
  const tsp::ValueRange range = file->tree().value_range();
  RenderScene whole(path, tsp::preset_transfer_function("sparse", range), tsp::CachePolicy::on, 80,
                    60, tsp::Metric::approximate);
  tsp::TransferFunction live_tf = whole.tf;
  auto live_ctx = create_offscreen_context(80, 60);
  VolumeRenderer live(*live_ctx, *whole.file, tsp::CachePolicy::on);
  live.set_transfer_function(live_tf);
  tsp::LazyErrors lazy(whole.file->tree(), tsp::Metric::approximate, live_tf);
  const tsp::Camera cam = whole.camera();
  auto compare = [&](const std::string& what) {
    for (tsp::Tolerances tol : {tsp::Tolerances{0, 0}, tsp::Tolerances{0.05, 0.02}}) {
      for (int step : {0, 3, 5}) {
        RenderSettings s;
        s.tol = tol;
        FrameReport a = whole.renderer->render(step, cam, s, whole.nodes);
        tsp::Image ia = whole.ctx->read_pixels();
        FrameReport b = live.render(step, cam, s, lazy);
        tsp::Image ib = live_ctx->read_pixels();
        EXPECT_EQ(ia.rgba, ib.rgba) << what << " step " << step << " tol " << tol.spatial;
        EXPECT_EQ(a.class_percent, b.class_percent) << what << " step " << step;
      }
    }
  };
  compare("before the edit");
  const tsp::TransferFunction filled = tsp::preset_transfer_function("filled", range);
  live_tf.set_entries(0, filled.entries());
  live.set_transfer_function(live_tf);
  whole.tf = filled;
  whole.renderer->set_transfer_function(filled);
  whole.baseline->set_transfer_function(filled);
  whole.metric = tsp::compute_errors(tsp::Metric::approximate, whole.file->tree(), filled);
  compare("after the edit");
  // Through the live metric: drop_unreachable agrees with the whole-tree metric's, and above
  // every error everything is flat, so no texture stays.
  EXPECT_EQ(live.drop_unreachable(lazy, {0, 0}, true),
            whole.renderer->drop_unreachable(whole.nodes, {0, 0}, true));
  const int before = live.texture_count();
  ASSERT_GT(before, 0);
  EXPECT_EQ(live.drop_unreachable(lazy, {1e9, 1e9}, true), before);
  EXPECT_EQ(live.texture_count(), 0);
}

// bricks_to_upload lists exactly what the frame reads: prefetched, the frame misses nothing in
// the brick cache and uploads their bytes; once drawn (cache on), nothing is left to upload.
TEST(VolumeRenderer, BricksToUploadAreWhatTheFrameReadsAndUploads) {
  auto src = tsp::make_generated_source("shock", {tsp::Dims{33, 30, 28}, 6});
  const std::string path = build_tsp(*src, "shock", {}, 8);
  auto file = tsp::TspFile::open(path);
  RenderScene scene(path, tsp::preset_transfer_function("filled", file->tree().value_range()),
                    tsp::CachePolicy::on, 64, 48, tsp::Metric::approximate);
  const tsp::Camera cam = scene.camera();
  for (auto [tol, span_step] : {std::pair{tsp::Tolerances{0, 0}, tsp::SpanStep::middle},
                                std::pair{tsp::Tolerances{0.05, 0.05}, tsp::SpanStep::middle},
                                std::pair{tsp::Tolerances{0.05, 0.05}, tsp::SpanStep::mean}}) {
    RenderSettings s;
    s.tol = tol;
    s.span_step = span_step;  // a span's mean reads every step of the span
    for (int step : {1, 4}) {
      const auto keys = scene.renderer->bricks_to_upload(step, cam, s, scene.nodes);
      ASSERT_FALSE(keys.empty());
      std::int64_t bytes = 0;
      for (const tsp::TextureKey& k : scene.renderer->textures_to_upload(step, cam, s, scene.nodes))
        bytes += tsp::texture_bytes(file->tree().octree(), k);
      tsp::BrickCache& bricks = scene.renderer->brick_cache();
      bricks.prefetch(keys);
      const std::int64_t misses = bricks.stats().misses;
      FrameReport r = scene.renderer->render(step, cam, s, scene.nodes);
      EXPECT_EQ(bricks.stats().misses, misses) << "step " << step;
      EXPECT_EQ(r.bytes_uploaded, bytes) << "step " << step;
      EXPECT_TRUE(scene.renderer->bricks_to_upload(step, cam, s, scene.nodes).empty());
    }
  }
}

// The renderer reads through the BrickStore interface: an in-memory store (no file) renders, its
// zero-tolerance frames match the baseline over the same store, and a failing store's error
// reaches the caller.
TEST(VolumeRenderer, RendersFromAnInMemoryBrickStore) {
  auto series = tsptest::MemorySeries::generate({30, 26, 20}, 4, [](int t, int x, int y, int z) {
    return float(std::sin(0.25 * x + 0.4 * t) * std::cos(0.2 * y) + 0.05 * z);
  });
  tsptest::MemoryBrickStore store(series, 8);
  auto ctx = create_offscreen_context(96, 72);
  VolumeRenderer renderer(*ctx, store, tsp::CachePolicy::on);
  BaselineRenderer baseline(*ctx, store);
  const tsp::TransferFunction tf = tsp::preset_transfer_function("filled", store.tree().value_range());
  renderer.set_transfer_function(tf);
  baseline.set_transfer_function(tf);
  const tsp::MetricResult m = tsp::compute_errors(tsp::Metric::reference, store.tree(), tf, &store, 1);
  tsp::WholeTreeMetric nodes(m);
  tsp::CameraParams p;
  p.width = 96;
  p.height = 72;
  const tsp::Camera cam(store.tree().octree().dims(), p);
  for (int step = 0; step < 4; ++step) {
    const FrameReport r = renderer.render(step, cam, RenderSettings{}, nodes);
    EXPECT_EQ(r.boxes, 1);  // the one-pass ray caster
    const tsp::Image a = ctx->read_pixels();
    baseline.render(step, cam, RenderSettings{});
    expect_close("memory_store_" + std::to_string(step), a, ctx->read_pixels(), 0.5, 3.0);
  }
  EXPECT_GT(store.reads(), 0);
  renderer.clear_textures();
  store.fail_reads(true);
  renderer.brick_cache().clear();
  EXPECT_THROW(renderer.render(0, cam, RenderSettings{}, nodes), tsp::IoError);
}

// With a one-byte upload budget each frame uploads one texture and draws the others flat;
// repeated frames of one step complete one texture at a time and then match the unlimited frame.
TEST(VolumeRenderer, UploadBudgetDefersTexturesUntilTheFrameCompletes) {
  auto src = tsp::make_generated_source("shock", {tsp::Dims{33, 30, 28}, 4});
  const std::string path = build_tsp(*src, "shock", {}, 8);
  auto file = tsp::TspFile::open(path);
  const auto tf = tsp::preset_transfer_function("filled", file->tree().value_range());
  RenderScene unlimited(path, tf, tsp::CachePolicy::on, 80, 60, tsp::Metric::approximate);
  RenderScene limited(path, tf, tsp::CachePolicy::on, 80, 60, tsp::Metric::approximate);
  const tsp::Camera cam = unlimited.camera();
  RenderSettings s;
  const tsp::Image expected = unlimited.tsp_frame(2, cam);
  const auto n =
      std::int64_t(limited.renderer->textures_to_upload(2, cam, s, limited.nodes).size());
  ASSERT_GT(n, 2);
  s.upload_budget = 1;
  for (std::int64_t f = 1; f <= n; ++f) {
    FrameReport r = limited.renderer->render(2, cam, s, limited.nodes);
    EXPECT_EQ(r.deferred_textures, n - f) << "frame " << f;
    EXPECT_EQ(r.complete(), f == n);
    EXPECT_EQ(limited.renderer->texture_count(), f);
    EXPECT_EQ(r.textures_resident, f);
  }
  const tsp::Image done = limited.ctx->read_pixels();
  EXPECT_EQ(done.rgba, expected.rgba);
}

}  // namespace
}  // namespace tspgl

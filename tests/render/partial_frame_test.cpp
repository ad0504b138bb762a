// Partial frames (VolumeRenderer::render with a PartialFrame; the player's refinement in bands,
// docs/player.md "Level of detail"): bands drawn over a coarser picture — one drawn at a smaller
// render target too — end as exactly the whole full-quality frame, partial-image reuse resumes
// once the last band is drawn, and a band drawn with other settings than the first says so.
#include <gtest/gtest.h>

#include <filesystem>

#include "render/volume_renderer.h"
#include "support/paths.h"
#include "support/render_scene.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image.h"
#include "tsp/source/open_source.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {
namespace {

namespace fs = std::filesystem;

TEST(VolumeRenderer, BandsOverACoarsePictureEndAsTheWholeFrame) {
  const fs::path h5 = tsptest::datasets_dir() / "samples" / "hotPlume_32.h5";
  tsp::SourceOptions so;
  so.field = "T";
  auto src = tsp::open_source(h5.string(), so);
  const std::string path = tsptest::build_tsp(*src, "plume_bands", {}, 8);
  auto file = tsp::TspFile::open(path);
  const auto tf = tsp::preset_transfer_function("filled", file->tree().value_range());
  tsptest::RenderScene scene(path, tf, tsp::CachePolicy::on);
  const tsp::Camera cam = scene.camera(35, 15);
  RenderSettings full;
  full.reuse_image = false;
  const tsp::Image whole = scene.frame(20, cam, full);

  for (double coarse_scale : {1.0, 0.5}) {
    RenderSettings coarse = full;
    coarse.spacing = 4;
    coarse.render_scale = coarse_scale;
    const tsp::Image under = scene.frame(20, cam, coarse);
    ASSERT_NE(under.rgba, whole.rgba) << "the coarse picture differs";
    // Three bands: the middle, then the bottom, then the top.
    const int w = cam.params().width, h = cam.params().height;
    const PixelRect bands[3] = {{0, h / 3, w, 2 * h / 3}, {0, 0, w, h / 3}, {0, 2 * h / 3, w, h}};
    RenderSettings s = full;
    s.reuse_image = true;
    for (int k = 0; k < 3; ++k) {
      PartialFrame part;
      part.rects = {bands[k]};
      part.first = k == 0;
      part.completes = k == 2;
      const FrameReport r = scene.renderer->render(20, cam, s, scene.nodes, {}, &part);
      EXPECT_FALSE(r.partial_stale);
      const tsp::Image now = scene.ctx->read_pixels();
      if (k < 2) {
        EXPECT_NE(now.rgba, whole.rgba) << "band " << k << " left part of the picture";
      }
    }
    const tsp::Image done = scene.ctx->read_pixels();
    EXPECT_EQ(done.rgba, whole.rgba) << "scale " << coarse_scale
                                     << tsptest::keep_failure("bands", done, whole);
    // The bands complete a picture: the next frame with nothing changed redraws nothing.
    const FrameReport again = scene.renderer->render(20, cam, s, scene.nodes);
    EXPECT_DOUBLE_EQ(again.redrawn_percent, 0.0);
    EXPECT_EQ(scene.ctx->read_pixels().rgba, whole.rgba);
  }

  // A band drawn with another spacing than the first: the earlier bands are stale.
  PartialFrame first, second;
  first.rects = {{0, 0, 10, 10}};
  first.first = true;
  second.rects = {{0, 10, 10, 20}};
  EXPECT_FALSE(scene.renderer->render(20, cam, full, scene.nodes, {}, &first).partial_stale);
  RenderSettings other = full;
  other.spacing = 2;
  EXPECT_TRUE(scene.renderer->render(20, cam, other, scene.nodes, {}, &second).partial_stale);
}

}  // namespace
}  // namespace tspgl

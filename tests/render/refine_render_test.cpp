// Refinement on OSMesa (tsp/frame/refine.h, RenderSettings::refine_tol): a one-voxel jump whose
// in-between values the TF makes opaque (the histogram map's rule for values no sample takes)
// is drawn where it lies at the default spacing — near the 1/16-voxel picture where the plain
// caster shows wood grain — and a smooth TF over smooth data is never refined, so its picture is
// the plain caster's exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "render/baseline_renderer.h"
#include "render/volume_renderer.h"
#include "support/function_scene.h"
#include "tsp/build/build.h"
#include "tsp/frame/refine.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/report/image_diff.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {
namespace {

constexpr double kReferenceSpacing = 1.0 / 16;

// One 65³ volume (bricks of 16) through tf, with the TSP renderer at zero tolerance and the
// baseline.
struct RefineScene : tsptest::FunctionScene {
  using FunctionScene::FunctionScene;
  tsp::Image frame(double refine_tol, bool dense, bool shade) {
    RenderSettings s;
    s.refine_tol = refine_tol;
    s.dense = dense;
    s.shade = shade;
    s.reuse_image = false;
    renderer->render(0, camera(), s, nodes);
    return ctx->read_pixels();
  }
  // The converged picture: the baseline every 1/16 voxel, not refined.
  tsp::Image reference(bool shade) {
    RenderSettings s;
    s.spacing = kReferenceSpacing;
    s.refine_tol = 0;
    s.shade = shade;
    baseline->render(0, camera(), s);
    return ctx->read_pixels();
  }
};

TEST(Refine, OneVoxelJumpIsDrawnWhereItLies) {
  // A ball of value 1 in a volume of 0: its surface is a one-voxel jump, and the TF makes the
  // values between the two states a dense orange band (opacity 0.8, as the histogram map makes
  // values no sample takes), the ball's inside a faint blue.
  const std::vector<tsp::TfPoint> pts{{0.0, {0, 0, 0, 0}},     {0.02, {0, 0, 0, 0}},
                                      {0.05, {1, 0.5f, 0, 0.8f}}, {0.95, {1, 0.5f, 0, 0.8f}},
                                      {0.98, {0.2f, 0.3f, 1, 0.05f}}, {1.0, {0.2f, 0.3f, 1, 0.05f}}};
  const tsp::TransferFunction tf = tsp::TransferFunction::from_points({0, 1}, pts);
  RefineScene scene("refine_ball", [](int x, int y, int z, int) {
    const double r = std::sqrt(double((x - 30) * (x - 30) + (y - 33) * (y - 33) + (z - 31) * (z - 31)));
    return r < 23.3 ? 1.f : 0.f;
  }, tf);
  for (bool shade : {false, true}) {
    const tsp::Image ref = scene.reference(shade);
    for (bool dense : {true, false}) {
      const tsp::DiffStats plain = tsp::diff_images(scene.frame(0, dense, shade), ref);
      const tsp::DiffStats refined =
          tsp::diff_images(scene.frame(tsp::kDefaultRefineTol, dense, shade), ref);
      const std::string what = std::string(shade ? "lit" : "unlit") + (dense ? ", dense" : ", bricks");
      std::printf("%s: plain %.3f / %.3f, refined %.3f / %.3f\n", what.c_str(), plain.mean,
                  plain.p99, refined.mean, refined.p99);
      EXPECT_LT(refined.mean, 0.5) << what << ": plain " << plain.mean << " / " << plain.p99
                                   << ", refined p99 " << refined.p99;
      EXPECT_LT(refined.p99, 5.0) << what;
      EXPECT_LT(refined.p99, 0.5 * plain.p99) << what;
    }
  }
}

TEST(Refine, SmoothDataUnderASmoothTfIsNeverRefined) {
  // A slow ramp through a ramp TF changes by far less than the tolerance between segments, so
  // every segment is the plain caster's sample: the same picture to the bit.
  const std::vector<tsp::TfPoint> pts{{0.0, {0, 0, 1, 0.01f}}, {1.0, {1, 0.6f, 0, 0.08f}}};
  const tsp::TransferFunction tf = tsp::TransferFunction::from_points({0, 1}, pts);
  RefineScene scene("refine_ramp",
                    [](int x, int y, int z, int) { return float(x + y + z) / 192; }, tf);
  for (bool dense : {true, false}) {
    const tsp::DiffStats d = tsp::diff_images(scene.frame(tsp::kDefaultRefineTol, dense, true),
                                              scene.frame(0, dense, true));
    EXPECT_EQ(d.max, 0.0) << "dense " << dense;
  }
}

}  // namespace
}  // namespace tspgl

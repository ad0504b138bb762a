// The player's viewer session (player/viewer_session.h), what File > Open creates, without a
// window: its metric is the one the library computes for the file and the TF (lazy or
// reference, following TF edits and replacements), its renderer draws what a renderer of its
// own draws, a new renderer keeps the window's programs, and a field swap hands back the file
// and renderer shown so far and takes a parked renderer back.
#include "player/viewer_session.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/function_tsp.h"
#include "support/render_scene.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/lazy_errors.h"

namespace {

using tspplayer::ViewerSession;

// A 2-step series of 17³ (8³ bricks): enough nodes for a cut, small enough for llvmpipe.
std::string series(const std::string& name, float phase) {
  return tsptest::build_function_tsp(
      name, {17, 17, 17},
      [phase](int x, int y, int z, int t) {
        return 0.5f + 0.5f * std::sin(0.4f * float(x + t) + phase) * std::cos(0.3f * float(y + z));
      },
      8, 2);
}

tsp::TransferFunction ramp() {
  tsp::TransferFunction tf;
  std::vector<tsp::Rgba> c(std::size_t(tf.size()));
  for (int j = 0; j < tf.size(); ++j) {
    const float u = float(j) / float(tf.size() - 1);
    c[std::size_t(j)] = {u, 0.5f, 1 - u, u * 0.8f};
  }
  tf.set_entries(0, c);
  return tf;
}

// The tests' view: 64×48 over the 17³ series.
constexpr int kWidth = 64, kHeight = 48;
tsp::Camera view() {
  tsp::CameraParams p;
  p.width = kWidth;
  p.height = kHeight;
  return tsp::Camera({17, 17, 17}, p);
}

// What the session's frame driver draws of step under its own metric.
tsp::Image drawn(ViewerSession& v, tspgl::GlContext& ctx, const tsp::Camera& cam,
                 const tsp::TransferFunction& tf, int step,
                 const tspgl::RenderSettings& s = {}) {
  tspgl::FrameRequest request;
  request.step = step;
  request.camera = &cam;
  request.settings = s;
  request.metric = &v.frame_metric();
  request.tf = &tf;
  v.driver().draw(request);
  return ctx.read_pixels();
}

TEST(ViewerSession, TheMetricIsTheLibrarysForTheFileAndFollowsTheTf) {
  const std::string path = series("metric", 0);
  tsp::TransferFunction tf = ramp();
  ViewerSession v(tsp::TspFile::open(path), tf, tsp::Metric::approximate);
  EXPECT_EQ(v.steps(), 2);
  EXPECT_FALSE(v.has_renderer());
  const std::unique_ptr<tsp::TspFile> same = tsp::TspFile::open(path);
  {
    tsp::LazyErrors expected(same->tree(), tsp::Metric::approximate, tf);
    v.evaluate_step(1);
    EXPECT_GT(v.metric_evaluations(), 0);
    const std::int64_t first = v.metric_evaluations();
    EXPECT_EQ(v.frame_metric().errors_for_step(1).spatial,
              expected.errors_for_step(1).spatial);
    EXPECT_EQ(v.errors_for_step(1).temporal, expected.errors_for_step(1).temporal);
    v.evaluate_step(1);  // memoised: nothing evaluated, the last count kept
    EXPECT_EQ(v.metric_evaluations(), first);
  }
  // The reference metric: computed in full for the TF as it is, again after an edit.
  v.set_metric(tsp::Metric::reference);
  EXPECT_EQ(v.metric(), tsp::Metric::reference);
  tsp::MetricResult ref = tsp::compute_errors(tsp::Metric::reference, same->tree(), tf,
                                              same.get(), 0);
  EXPECT_EQ(v.frame_metric().errors_for_step(0).spatial, ref.errors.spatial);
  EXPECT_EQ(v.metric_evaluations(), std::int64_t(ref.transparent.size()));
  EXPECT_EQ(v.errors_for_step(0).spatial, ref.errors.spatial);
  const std::vector<tsp::Rgba> clear(8, tsp::Rgba{0, 0, 0, 0});
  tf.set_entries(0, clear);  // the low values transparent
  ref = tsp::compute_errors(tsp::Metric::reference, same->tree(), tf, same.get(), 0);
  EXPECT_EQ(v.errors_for_step(0).spatial, ref.errors.spatial);  // recomputed for the edit
  EXPECT_EQ(v.frame_metric().errors_for_step(0).spatial, ref.errors.spatial);
  // Back to a lazy metric, over the edited TF; a replaced TF is seen whole.
  v.set_metric(tsp::Metric::perceptual);
  tsp::LazyErrors perceptual(same->tree(), tsp::Metric::perceptual, tf);
  EXPECT_EQ(v.frame_metric().errors_for_step(0).spatial, perceptual.errors_for_step(0).spatial);
  tf.assign(ramp());
  v.tf_replaced();
  tsp::LazyErrors replaced(same->tree(), tsp::Metric::perceptual, tf);
  EXPECT_EQ(v.frame_metric().errors_for_step(0).spatial, replaced.errors_for_step(0).spatial);
}

// File > Open and a field switch with the reference metric chosen: the lazy metric cannot
// serve it (LazyErrors throws), so opening threw after the old renderer was gone and the next
// frame crashed; the session computes the new file's reference errors instead.
TEST(ViewerSession, TheReferenceMetricSurvivesAnOpenAndAFieldSwap) {
  const std::string a = series("ref_a", 0), b = series("ref_b", 1.5f);
  const tsp::TransferFunction tf = ramp();
  const std::unique_ptr<tsp::TspFile> fa = tsp::TspFile::open(a), fb = tsp::TspFile::open(b);
  const tsp::MetricResult ref_a =
      tsp::compute_errors(tsp::Metric::reference, fa->tree(), tf, fa.get(), 0);
  const tsp::MetricResult ref_b =
      tsp::compute_errors(tsp::Metric::reference, fb->tree(), tf, fb.get(), 0);
  ASSERT_NE(ref_a.errors.spatial, ref_b.errors.spatial);
  std::unique_ptr<ViewerSession> v;
  ASSERT_NO_THROW(v = std::make_unique<ViewerSession>(tsp::TspFile::open(a), tf,
                                                      tsp::Metric::reference));
  EXPECT_EQ(v->errors_for_step(0).spatial, ref_a.errors.spatial);
  v->evaluate_step(0);  // nothing lazy to evaluate
  v->tf_replaced();     // nothing lazy to tell
  std::shared_ptr<tspgl::SliceCompositor> programs;
  v->swap_field(tsp::TspFile::open(b), programs);
  EXPECT_EQ(v->errors_for_step(0).spatial, ref_b.errors.spatial);  // b's, not a's left over
  EXPECT_EQ(v->frame_metric().errors_for_step(1).temporal, ref_b.errors.temporal);
  v->set_metric(tsp::Metric::approximate);  // and a lazy metric again afterwards
  tsp::LazyErrors lazy(fb->tree(), tsp::Metric::approximate, tf);
  EXPECT_EQ(v->errors_for_step(0).spatial, lazy.errors_for_step(0).spatial);
}

TEST(ViewerSession, ItsRendererDrawsTheFileAndAFieldSwapHandsTheOldOneBack) {
  const std::string a = series("a", 0), b = series("b", 1.5f);
  const tsp::TransferFunction tf = ramp();
  const std::unique_ptr<tspgl::GlContext> ctx = tspgl::create_offscreen_context(kWidth, kHeight);
  std::shared_ptr<tspgl::SliceCompositor> programs;
  tspgl::RenderSettings s;
  const tsp::Camera cam = view();
  // What a renderer of its own draws of a file at full quality.
  const auto own_picture = [&](const std::string& path) {
    const std::unique_ptr<tsp::TspFile> f = tsp::TspFile::open(path);
    tspgl::VolumeRenderer r(*ctx, *f, tsp::CachePolicy::on);
    r.set_transfer_function(tf);
    const tsp::MetricResult m = tsp::compute_errors(tsp::Metric::approximate, f->tree(), tf,
                                                    f.get(), 0);
    tsp::WholeTreeMetric nodes(m);
    r.render(1, cam, s, nodes);
    return ctx->read_pixels();
  };
  const auto drawn_1 = [&](ViewerSession& v) { return drawn(v, *ctx, cam, tf, 1, s); };
  const tsp::Image picture_a = own_picture(a), picture_b = own_picture(b);
  ASSERT_NE(picture_a.rgba, picture_b.rgba);

  ViewerSession v(tsp::TspFile::open(a), tf, tsp::Metric::approximate);
  v.make_renderer(*ctx, tsp::CachePolicy::on, 64 << 20, 64 << 20, programs);
  ASSERT_TRUE(v.has_renderer());
  EXPECT_EQ(drawn_1(v).rgba, picture_a.rgba);
  // A new renderer (a cache change) keeps the window's compiled programs.
  v.make_renderer(*ctx, tsp::CachePolicy::off, 64 << 20, 64 << 20, programs);
  ASSERT_TRUE(programs);
  EXPECT_EQ(v.renderer().compositor(), programs);
  EXPECT_EQ(drawn_1(v).rgba, picture_a.rgba);
  // A field swap: b shown, a's file and renderer handed back; drawing b needs a renderer.
  const tsp::TspFile* file_a = &v.file();
  const tspgl::VolumeRenderer* renderer_a = &v.renderer();
  auto [old_file, old_renderer] = v.swap_field(tsp::TspFile::open(b), programs);
  EXPECT_EQ(old_file.get(), file_a);
  EXPECT_EQ(old_renderer.get(), renderer_a);
  EXPECT_FALSE(v.has_renderer());
  v.make_renderer(*ctx, tsp::CachePolicy::on, 64 << 20, 64 << 20, programs);
  EXPECT_EQ(v.renderer().compositor(), programs);
  EXPECT_EQ(drawn_1(v).rgba, picture_b.rgba);
  // Back to a: its own renderer adopted, drawing a again.
  auto [file_b, renderer_b] = v.swap_field(std::move(old_file), programs);
  v.adopt_renderer(std::move(old_renderer));
  EXPECT_EQ(&v.renderer(), renderer_a);
  EXPECT_EQ(drawn_1(v).rgba, picture_a.rgba);
}

TEST(ViewerSession, OpeningAnotherFileReplacesTheWholeSession) {
  const std::string a = series("open_a", 0), b = series("open_b", 1.5f);
  const tsp::TransferFunction tf = ramp();
  const std::unique_ptr<tspgl::GlContext> ctx = tspgl::create_offscreen_context(kWidth, kHeight);
  std::shared_ptr<tspgl::SliceCompositor> programs;
  const tsp::Camera cam = view();
  const auto drawn_0 = [&](ViewerSession& v) { return drawn(v, *ctx, cam, tf, 0); };
  // As the player's File > Open: the programs taken from the old renderer, the old session
  // dropped, a new one made over the new file with the same TF object.
  auto v = std::make_unique<ViewerSession>(tsp::TspFile::open(a), tf, tsp::Metric::approximate);
  v->make_renderer(*ctx, tsp::CachePolicy::on, 64 << 20, 64 << 20, programs);
  const tsp::Image first_a = drawn_0(*v);
  programs = v->renderer().compositor();
  v = std::make_unique<ViewerSession>(tsp::TspFile::open(b), tf, tsp::Metric::approximate);
  EXPECT_FALSE(v->has_renderer());
  v->make_renderer(*ctx, tsp::CachePolicy::on, 64 << 20, 64 << 20, programs);
  EXPECT_EQ(v->renderer().compositor(), programs);
  const tsp::Image then_b = drawn_0(*v);
  EXPECT_NE(then_b.rgba, first_a.rgba);
  // And back: the same picture of a as the first session drew.
  v = std::make_unique<ViewerSession>(tsp::TspFile::open(a), tf, tsp::Metric::approximate);
  v->make_renderer(*ctx, tsp::CachePolicy::on, 64 << 20, 64 << 20, programs);
  EXPECT_EQ(drawn_0(*v).rgba, first_a.rgba);
}

}  // namespace

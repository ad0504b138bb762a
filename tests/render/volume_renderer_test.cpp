// The renderer on OSMesa against analytic answers: a constant cube against front-to-back
// compositing, a flat node's exact exponential, the eye inside, skipped transparent children,
// stretched voxels, a second field's programs and bricks, a pre-integrated ramp. (Generated and
// real data, reuse, caches and budgets: volume_renderer_data_test.cpp.) Failing image
// comparisons write actual, expected and difference PNGs under test-output/.
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
#include "tsp/metric/preintegration.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image.h"
#include "tsp/frame/refine.h"
#include "tsp/report/image_diff.h"
#include "tsp/source/open_source.h"
#include "tsp/source/procedural/generate.h"
#include "tsp/store/tsp_file.h"
#include "tsp/tree/traversal.h"

namespace tspgl {
namespace {

namespace fs = std::filesystem;

using namespace tsptest;  // the render scene, build_tsp and the image checks

TEST(VolumeRenderer, ConstantCubeMatchesFrontToBackCompositing) {
  // 33³ samples: geometry [0, 32]³. Looking along +y through the centre, the planes at
  // y = (k + ½)·0.5 cut the ray 64 times, each slice with α' = 1 − (1 − α)^0.5.
  auto src = tsptest::MemorySource::from_function({33, 33, 33}, 2,
                                                  [](int, int, int, int) { return 0.5f; });
  const std::string path = build_tsp(src, "cube", tsp::ValueRange{0, 1});
  const tsp::Rgba c{0.9f, 0.5f, 0.2f, 0.04f};
  RenderScene scene(path, flat_tf(c), tsp::CachePolicy::on);
  const tsp::Camera cam = scene.camera(0, 0);
  const double opacity = 1 - std::pow(1 - double(c.a), 0.5 * 64);
  const std::uint8_t want[3] = {std::uint8_t(std::lround(255 * c.r * opacity)),
                                std::uint8_t(std::lround(255 * c.g * opacity)),
                                std::uint8_t(std::lround(255 * c.b * opacity))};
  for (bool baseline : {false, true}) {
    tsp::Image img = baseline ? scene.baseline_frame(0, cam) : scene.tsp_frame(0, cam);
    const std::uint8_t* px = img.at(img.width / 2, img.height / 2);
    tsp::Luv got = tsp::srgb8_to_luv(px[0], px[1], px[2]);
    tsp::Luv exp = tsp::srgb8_to_luv(want[0], want[1], want[2]);
    EXPECT_LT(tsp::delta_e_luv(got, exp), 1.0)
        << (baseline ? "baseline" : "tsp") << ": got " << int(px[0]) << "," << int(px[1]) << ","
        << int(px[2]) << " want " << int(want[0]) << "," << int(want[1]) << "," << int(want[2]);
    // Outside the cube's projection the background stays black.
    const std::uint8_t* corner = img.at(0, 0);
    EXPECT_EQ(corner[0] + corner[1] + corner[2], 0);
  }
}

// A coherent node drawn as one box composites exactly: α = 1 − (1 − α₁)^L over the ray's depth
// L through the box. Seen obliquely, the centre ray of a 32³ cube runs L = 2·min_a 16/|d_a|;
// flat slices converge to the same picture as the spacing goes to zero.
TEST(VolumeRenderer, FlatNodeDrawnOnceIsTheExactExponential) {
  auto src = tsptest::MemorySource::from_function({33, 33, 33}, 2,
                                                  [](int, int, int, int) { return 0.5f; });
  const std::string path = build_tsp(src, "flat_cube", tsp::ValueRange{0, 1});
  const tsp::Rgba c{0.9f, 0.5f, 0.2f, 0.03f};
  RenderScene scene(path, flat_tf(c), tsp::CachePolicy::on);
  const tsp::Camera cam = scene.camera(30, 20);
  const auto d = cam.direction();
  double len = 1e300;
  for (double v : d) len = std::min(len, 16.0 / std::max(std::abs(v), 1e-12));
  len *= 2;
  const double opacity = 1 - std::pow(1 - double(c.a), len);
  const std::uint8_t want[3] = {std::uint8_t(std::lround(255 * c.r * opacity)),
                                std::uint8_t(std::lround(255 * c.g * opacity)),
                                std::uint8_t(std::lround(255 * c.b * opacity))};
  auto frame = [&](Compositing comp, bool exact, double spacing) {
    RenderSettings s;
    s.compositing = comp;
    s.exact_flat = exact;
    s.spacing = spacing;
    const FrameReport r = scene.renderer->render(0, cam, s, scene.nodes);
    EXPECT_DOUBLE_EQ(r.class_percent[std::size_t(tsp::DrawClass::untextured)], 100.0);
    return scene.ctx->read_pixels();
  };
  const tsp::Image exact_rays = frame(Compositing::rays, true, 0.5);
  const tsp::Image exact_box = frame(Compositing::slices, true, 0.5);
  const tsp::Image fine_slices = frame(Compositing::slices, false, 1.0 / 16);
  for (const tsp::Image* img : {&exact_rays, &exact_box}) {
    const std::uint8_t* px = img->at(img->width / 2, img->height / 2);
    EXPECT_LT(tsp::delta_e_luv(tsp::srgb8_to_luv(px[0], px[1], px[2]),
                               tsp::srgb8_to_luv(want[0], want[1], want[2])),
              0.5)
        << "got " << int(px[0]) << "," << int(px[1]) << "," << int(px[2]) << " want "
        << int(want[0]) << "," << int(want[1]) << "," << int(want[2]);
  }
  expect_close("flat_rays_vs_box", exact_rays, exact_box, 0.05, 0.5);
  expect_close("flat_exact_vs_fine_slices", exact_rays, fine_slices, 0.5, 3.0);
}

// Issue 31 item 4: a camera inside the volume (CameraParams::eye). From (16, 8, 16) of a constant
// 32³ cube, looking along +y, the centre ray runs L = 24 voxels to the far face: its pixel is
// the exact exponential α = 1 − (1 − α₁)^24, in the ray caster (rays starting at the eye) and
// in slices (the planes in front of the near plane).
TEST(VolumeRenderer, AnEyeInsideTheCubeSeesTheExponentialOfItsRayToTheFarFace) {
  auto src = tsptest::MemorySource::from_function({33, 33, 33}, 2,
                                                  [](int, int, int, int) { return 0.5f; });
  const std::string path = build_tsp(src, "inside_cube", tsp::ValueRange{0, 1});
  const tsp::Rgba c{0.9f, 0.5f, 0.2f, 0.03f};
  RenderScene scene(path, flat_tf(c), tsp::CachePolicy::on);
  tsp::CameraParams p;
  p.projection = tsp::Projection::perspective;
  p.azimuth_deg = 0;  // looks along +y
  p.elevation_deg = 0;
  p.width = scene.ctx->width();
  p.height = scene.ctx->height();
  p.eye = std::array<double, 3>{16, 8, 16};
  const tsp::Camera cam(scene.file->tree().octree().dims(), p);
  const double opacity = 1 - std::pow(1 - double(c.a), 24.0);
  const std::uint8_t want[3] = {std::uint8_t(std::lround(255 * c.r * opacity)),
                                std::uint8_t(std::lround(255 * c.g * opacity)),
                                std::uint8_t(std::lround(255 * c.b * opacity))};
  for (Compositing comp : {Compositing::rays, Compositing::slices}) {
    RenderSettings s;
    s.compositing = comp;
    s.exact_flat = true;
    s.shade = false;
    scene.renderer->render(0, cam, s, scene.nodes);
    const tsp::Image img = scene.ctx->read_pixels();
    const std::uint8_t* px = img.at(img.width / 2, img.height / 2);
    EXPECT_LT(tsp::delta_e_luv(tsp::srgb8_to_luv(px[0], px[1], px[2]),
                               tsp::srgb8_to_luv(want[0], want[1], want[2])),
              0.5)
        << to_string(comp) << ": got " << int(px[0]) << "," << int(px[1]) << "," << int(px[2])
        << " want " << int(want[0]) << "," << int(want[1]) << "," << int(want[2]);
    // The whole image is inside the cube: no background pixel.
    const std::uint8_t* corner = img.at(0, 0);
    EXPECT_GT(corner[0] + corner[1] + corner[2], 0) << to_string(comp);
  }
}

// Issue 9 item 5: the left half transparent (value 0 under a TF that is transparent there), the
// right half a smooth ramp; at a tolerance that makes the root coherent, the paper's rule draws
// the root flat — its mean colour haze over the empty half too — and ours draws its children,
// skipping the transparent ones as zero tolerance does: seen along y, the left half's pixels stay
// background with our rule, and the right half is drawn.
TEST(VolumeRenderer, TransparentChildrenOfACoherentNodeStaySkipped) {
  // 31³ in bricks of 16 samples: 2 × 2 × 2 bricks sharing the layer x = 15.
  auto src = tsptest::MemorySource::from_function({31, 31, 31}, 2, [](int x, int, int z, int) {
    return x <= 15 ? 0.f : 0.6f + 0.01f * float(z % 4);
  });
  const std::string path = build_tsp(src, "half_empty", tsp::ValueRange{0, 1});
  std::vector<tsp::TfPoint> pts = {{0.0, {0.f, 0.f, 0.f, 0.f}}, {0.5, {0.f, 0.f, 0.f, 0.f}},
                                   {0.55, {0.9f, 0.5f, 0.2f, 0.05f}}, {1.0, {0.9f, 0.5f, 0.2f, 0.05f}}};
  RenderScene scene(path, tsp::TransferFunction::from_points({0, 1}, pts), tsp::CachePolicy::on);
  const tsp::Camera cam = scene.camera(0, 0);
  auto frame = [&](bool skip) {
    RenderSettings s;
    s.tol = {1e9, 1e9};
    s.skip_transparent = skip;
    const FrameReport r = scene.renderer->render(0, cam, s, scene.nodes);
    return std::pair{scene.ctx->read_pixels(), r};
  };
  const auto [paper, paper_report] = frame(false);
  const auto [ours, ours_report] = frame(true);
  EXPECT_DOUBLE_EQ(paper_report.class_percent[std::size_t(tsp::DrawClass::untextured)], 100.0);
  EXPECT_GT(ours_report.class_percent[std::size_t(tsp::DrawClass::not_rendered)], 40.0);
  // x grows to the right on screen looking along +y (azimuth 0); a quarter of the width from
  // either side is well inside each half.
  const int y = scene.ctx->height() / 2, left = scene.ctx->width() / 2 - scene.ctx->width() / 8,
            right = scene.ctx->width() / 2 + scene.ctx->width() / 8;
  auto sum = [&](const tsp::Image& img, int x) {
    const std::uint8_t* px = img.at(x, y);
    return px[0] + px[1] + px[2];
  };
  const bool left_is_empty_half = sum(ours, left) == 0;
  const int empty_x = left_is_empty_half ? left : right, full_x = left_is_empty_half ? right : left;
  EXPECT_EQ(sum(ours, empty_x), 0) << "our rule drew the transparent half";
  EXPECT_GT(sum(paper, empty_x), 0) << "the paper's flat root should cover the transparent half";
  EXPECT_GT(sum(ours, full_x), 0);
}

// Anisotropic voxels (spacing 2 along x): a 17×33×33 grid is the box of a 33³ grid of cubes.
// Seen along y, the rays cross the same 64 slices and the two pictures agree; seen obliquely,
// samples still lie `spacing` apart along the rays (in sample units), so the centre pixel is the
// exponential over the centre ray's length through the box in sample units — for the one-pass
// caster, slicing and the baseline alike.
TEST(VolumeRenderer, StretchedVoxelsShowThePhysicalBoxSampledAlongTheRays) {
  const auto constant = [](int, int, int, int) { return 0.5f; };
  auto narrow = tsptest::MemorySource::from_function({17, 33, 33}, 1, constant);
  auto cube = tsptest::MemorySource::from_function({33, 33, 33}, 1, constant);
  const tsp::Rgba c{0.9f, 0.5f, 0.2f, 0.04f};
  RenderScene stretched(build_tsp(narrow, "narrow", tsp::ValueRange{0, 1}), flat_tf(c),
                        tsp::CachePolicy::on);
  RenderScene cubes(build_tsp(cube, "cubes", tsp::ValueRange{0, 1}), flat_tf(c),
                    tsp::CachePolicy::on);
  auto camera = [](const RenderScene& sc, double az, double el, std::array<double, 3> voxel) {
    tsp::CameraParams p;
    p.azimuth_deg = az;
    p.elevation_deg = el;
    p.width = sc.ctx->width();
    p.height = sc.ctx->height();
    p.voxel_size = voxel;
    return tsp::Camera(sc.file->tree().octree().dims(), p);
  };
  auto frame = [](RenderScene& sc, const tsp::Camera& cam, Compositing comp, bool baseline) {
    RenderSettings s;
    s.compositing = comp;
    s.exact_flat = false;  // textured and flat nodes alike sample every spacing
    if (baseline)
      sc.baseline->render(0, cam, s);
    else
      sc.renderer->render(0, cam, s, sc.nodes);
    return sc.ctx->read_pixels();
  };
  const tsp::Camera along_y = camera(stretched, 0, 0, {2, 1, 1});
  const tsp::Image want = frame(cubes, camera(cubes, 0, 0, {1, 1, 1}), Compositing::rays, false);
  for (Compositing comp : {Compositing::rays, Compositing::slices})
    expect_close("stretched_along_y", frame(stretched, along_y, comp, false), want, 0.5, 2.0);
  expect_close("stretched_along_y_baseline", frame(stretched, along_y, Compositing::slices, true),
               want, 0.5, 2.0);

  const tsp::Camera oblique = camera(stretched, 30, 20, {2, 1, 1});
  const auto r = oblique.ray_direction();
  const double half[3] = {8, 16, 16};
  double len = 1e300;
  for (int a = 0; a < 3; ++a) len = std::min(len, half[a] / std::max(std::abs(r[a]), 1e-12));
  len *= 2;  // through the centre: twice the way out
  const double opacity = 1 - std::pow(1 - double(c.a), len);
  const tsp::Luv expected = tsp::srgb8_to_luv(std::uint8_t(std::lround(255 * c.r * opacity)),
                                              std::uint8_t(std::lround(255 * c.g * opacity)),
                                              std::uint8_t(std::lround(255 * c.b * opacity)));
  for (int k = 0; k < 3; ++k) {
    const tsp::Image img = frame(stretched, oblique, k == 1 ? Compositing::slices : Compositing::rays,
                                 k == 2);
    const std::uint8_t* px = img.at(img.width / 2, img.height / 2);
    EXPECT_LT(tsp::delta_e_luv(tsp::srgb8_to_luv(px[0], px[1], px[2]), expected), 1.0)
        << "case " << k << ": got " << int(px[0]) << "," << int(px[1]) << "," << int(px[2])
        << " for opacity " << opacity << " over " << len << " samples";
  }
}

// A BrickStore that counts its reads (for the field-switch test).
class CountingStore : public tsp::BrickStore {
 public:
  explicit CountingStore(const tsp::TspFile& f) : f_(f) {}
  const tsp::TspTree& tree() const override { return f_.tree(); }
  void read_brick(int b, int t, std::span<std::uint16_t> out) const override {
    ++reads;
    f_.read_brick(b, t, out);
  }
  mutable std::atomic<int> reads{0};

 private:
  const tsp::TspFile& f_;
};

// Two fields of one file drawn by two renderers sharing one compositor (the player's field
// switch): drawing the second reads only its own bricks, and its picture is what a renderer of
// its own draws.
TEST(VolumeRenderer, ASecondFieldSharesTheProgramsAndReadsOnlyItsOwnBricks) {
  const std::string path = (tsptest::temp_dir() / "fields.tsp").string();
  tsp::BuildOptions o;
  o.brick_size = 8;
  tsp::build_tsp_fields(
      [](const std::string& f) -> std::unique_ptr<tsp::VolumeSource> {
        return std::make_unique<tsptest::MemorySource>(tsptest::MemorySource::from_function(
            {20, 18, 16}, 2, [&f](int x, int y, int z, int t) {
              return f == "a" ? float(x + y + z + t) : float((x * y + z * 7 + t) % 13);
            }));
      },
      {"a", "b"}, path, o);
  auto fa = tsp::TspFile::open(path, "a"), fb = tsp::TspFile::open(path, "b");
  CountingStore sa(*fa), sb(*fb);
  auto ctx = create_offscreen_context(96, 72);
  tsp::CameraParams p;
  p.width = 96;
  p.height = 72;
  const tsp::Camera cam(fa->tree().octree().dims(), p);
  auto draw = [&](VolumeRenderer& r, const tsp::TspFile& f) {
    const auto tf = tsp::preset_transfer_function("filled", f.tree().value_range());
    r.set_transfer_function(tf);
    tsp::MetricResult m = tsp::compute_errors(tsp::Metric::approximate, f.tree(), tf, nullptr, 1);
    tsp::WholeTreeMetric nodes(m);
    r.render(0, cam, RenderSettings{}, nodes);
    return ctx->read_pixels();
  };
  VolumeRenderer ra(*ctx, sa, tsp::CachePolicy::on);
  draw(ra, *fa);
  const int a_reads = sa.reads;
  EXPECT_GT(a_reads, 0);
  VolumeRenderer rb(*ctx, sb, tsp::CachePolicy::on, kDefaultTextureBudget, kDefaultBrickBudget,
                    ra.compositor());
  EXPECT_EQ(rb.compositor(), ra.compositor());
  const tsp::Image shared = draw(rb, *fb);
  EXPECT_EQ(sa.reads, a_reads);  // nothing of field a
  EXPECT_GT(sb.reads, 0);
  VolumeRenderer own(*ctx, *fb, tsp::CachePolicy::on);
  expect_close("second_field", shared, draw(own, *fb), 0.01, 0.1);
}

// Pre-integration: along the centre ray the value ramps linearly so that the half-way points
// between samples (spacing 4) fall on entry centres of an 8-entry TF; each sample's segment is
// then exactly one table entry, and the pixel is the front-to-back composite of
// integrate_segment over those segments — for every compositing, TSP and baseline.
TEST(VolumeRenderer, PreintegratedRampMatchesTheSegmentFormula) {
  constexpr double kSpacing = 4;
  auto src = tsptest::MemorySource::from_function(
      {17, 37, 17}, 2, [](int, int y, int, int) { return float(y / 32.0 + 1.0 / 16); });
  const std::string path = build_tsp(src, "ramp", tsp::ValueRange{0, 1});
  tsp::TransferFunction tf({0, 1}, 8);
  for (int j = 0; j < 8; ++j) tf.set_entry(j, {j / 7.f, 1 - j / 7.f, 0.5f, 0.03f + 0.02f * j});
  RenderScene scene(path, tf, tsp::CachePolicy::on);
  const tsp::Camera cam = scene.camera(0, 0);  // along +y: y = 0 in front
  double r = 0, g = 0, b = 0, t = 1;
  // Segments [4j, 4j + 4] centred on the planes y = 4j + 2; the last two lie beyond u = 1,
  // clamped into entry 7.
  for (int j = 0; j < 9; ++j) {
    const tsp::Rgba c = tsp::integrate_segment(tf, (j + 0.5) / 8, (j + 1.5) / 8, kSpacing);
    r += t * c.r;
    g += t * c.g;
    b += t * c.b;
    t *= 1 - c.a;
  }
  const tsp::Luv want = tsp::srgb8_to_luv(std::uint8_t(std::lround(255 * r)),
                                          std::uint8_t(std::lround(255 * g)),
                                          std::uint8_t(std::lround(255 * b)));
  for (Compositing comp : {Compositing::slices, Compositing::boxes, Compositing::rays}) {
    for (bool baseline : {false, true}) {
      RenderSettings s;
      s.compositing = comp;
      s.spacing = kSpacing;
      s.preintegrated = true;
      s.shade = false;  // the segment formula above is the unlit colour
      if (baseline)
        scene.baseline->render(0, cam, s);
      else
        scene.renderer->render(0, cam, s, scene.nodes);
      const tsp::Image img = scene.ctx->read_pixels();
      // A few pixels off the centre, whose ray would run exactly along brick faces (x = z = 8).
      const std::uint8_t* px = img.at(img.width / 2 + 5, img.height / 2 + 3);
      // Bricks meet at y = 12 and 24, on half-way points and off the sample planes: drawn brick
      // by brick (slices, boxes) no half-way point needs the neighbour brick's samples.
      EXPECT_LT(tsp::delta_e_luv(tsp::srgb8_to_luv(px[0], px[1], px[2]), want), 1.0)
          << to_string(comp) << (baseline ? " baseline" : " tsp") << ": got " << int(px[0])
          << "," << int(px[1]) << "," << int(px[2]) << " want " << 255 * r << "," << 255 * g
          << "," << 255 * b;
    }
  }
}

}  // namespace
}  // namespace tspgl

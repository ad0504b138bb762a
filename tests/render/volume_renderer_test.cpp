// The renderer on OSMesa: an analytic constant cube, zero-tolerance TSP frames against the
// non-TSP baseline on generated and real data, cache on/off giving identical images, and the
// class shares of a frame against the traversal. Failing image comparisons write actual,
// expected and difference PNGs under test-output/ in the working directory.
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

std::string build(tsp::VolumeSource& src, const std::string& name, std::optional<tsp::ValueRange> range = {},
                  int brick = 16) {
  std::string path = (tsptest::temp_dir() / (name + ".tsp")).string();
  tsp::BuildOptions o;
  o.brick_size = brick;
  o.range = range;
  tsp::build_tsp_file(src, path, o);
  return path;
}

// Writes actual / expected / difference images for a failed comparison and returns the folder.
std::string keep_failure(const std::string& name, const tsp::Image& actual,
                         const tsp::Image& expected) {
  fs::path dir = fs::current_path() / "test-output" / name;
  fs::create_directories(dir);
  tsp::write_png((dir / "actual.png").string(), actual);
  tsp::write_png((dir / "expected.png").string(), expected);
  tsp::Image diff;
  tsp::diff_images(actual, expected, &diff);
  tsp::write_png((dir / "difference.png").string(), diff);
  return dir.string();
}

void expect_close(const std::string& name, const tsp::Image& actual, const tsp::Image& expected,
                  double max_mean, double max_p99) {
  tsp::DiffStats d = tsp::diff_images(actual, expected);
  bool ok = d.mean < max_mean && d.p99 < max_p99;
  EXPECT_TRUE(ok) << name << ": mean ΔE " << d.mean << " (limit " << max_mean << "), p99 " << d.p99
                  << " (limit " << max_p99 << "), max " << d.max << "; images in "
                  << (ok ? "" : keep_failure(name, actual, expected));
}

struct Scene {
  std::unique_ptr<tsp::TspFile> file;
  std::unique_ptr<GlContext> ctx;
  std::unique_ptr<VolumeRenderer> renderer;
  std::unique_ptr<BaselineRenderer> baseline;
  tsp::TransferFunction tf;
  tsp::MetricResult metric;
  tsp::WholeTreeMetric nodes{metric};  ///< metric as the renderer reads it
  Scene(const std::string& path, const tsp::TransferFunction& t, tsp::CachePolicy cache, int w = 160,
        int h = 120, tsp::Metric m = tsp::Metric::reference)
      : file(tsp::TspFile::open(path)), ctx(create_offscreen_context(w, h)), tf(t) {
    renderer = std::make_unique<VolumeRenderer>(*ctx, *file, cache);
    renderer->set_transfer_function(tf);
    baseline = std::make_unique<BaselineRenderer>(*ctx, *file);
    baseline->set_transfer_function(tf);
    metric = tsp::compute_errors(m, file->tree(), tf, file.get(), 0);
  }
  tsp::Camera camera(double az = 30, double el = 20, bool perspective = false) const {
    tsp::CameraParams p;
    p.projection = perspective ? tsp::Projection::perspective : tsp::Projection::orthographic;
    p.azimuth_deg = az;
    p.elevation_deg = el;
    p.width = ctx->width();
    p.height = ctx->height();
    return tsp::Camera(file->tree().octree().dims(), p);
  }
  bool shade = true;  ///< frames lit (the default) or unlit
  tsp::Image tsp_frame(int step, const tsp::Camera& cam, tsp::Tolerances tol = {}) {
    RenderSettings s;
    s.tol = tol;
    s.shade = shade;
    renderer->render(step, cam, s, nodes);
    return ctx->read_pixels();
  }
  tsp::Image baseline_frame(int step, const tsp::Camera& cam) {
    RenderSettings s;
    s.shade = shade;
    baseline->render(step, cam, s);
    return ctx->read_pixels();
  }
};

tsp::TransferFunction flat_tf(tsp::Rgba c) {
  std::vector<tsp::TfPoint> pts = {{0.0, c}, {1.0, c}};
  return tsp::TransferFunction::from_points({0, 1}, pts);
}

TEST(VolumeRenderer, ConstantCubeMatchesFrontToBackCompositing) {
  // 33³ samples: geometry [0, 32]³. Looking along +y through the centre, the planes at
  // y = (k + ½)·0.5 cut the ray 64 times, each slice with α' = 1 − (1 − α)^0.5.
  auto src = tsptest::MemorySource::from_function({33, 33, 33}, 2,
                                                  [](int, int, int, int) { return 0.5f; });
  const std::string path = build(src, "cube", tsp::ValueRange{0, 1});
  const tsp::Rgba c{0.9f, 0.5f, 0.2f, 0.04f};
  Scene scene(path, flat_tf(c), tsp::CachePolicy::on);
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
  const std::string path = build(src, "flat_cube", tsp::ValueRange{0, 1});
  const tsp::Rgba c{0.9f, 0.5f, 0.2f, 0.03f};
  Scene scene(path, flat_tf(c), tsp::CachePolicy::on);
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
  const std::string path = build(src, "inside_cube", tsp::ValueRange{0, 1});
  const tsp::Rgba c{0.9f, 0.5f, 0.2f, 0.03f};
  Scene scene(path, flat_tf(c), tsp::CachePolicy::on);
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
  const std::string path = build(src, "half_empty", tsp::ValueRange{0, 1});
  std::vector<tsp::TfPoint> pts = {{0.0, {0.f, 0.f, 0.f, 0.f}}, {0.5, {0.f, 0.f, 0.f, 0.f}},
                                   {0.55, {0.9f, 0.5f, 0.2f, 0.05f}}, {1.0, {0.9f, 0.5f, 0.2f, 0.05f}}};
  Scene scene(path, tsp::TransferFunction::from_points({0, 1}, pts), tsp::CachePolicy::on);
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
  Scene stretched(build(narrow, "narrow", tsp::ValueRange{0, 1}), flat_tf(c), tsp::CachePolicy::on);
  Scene cubes(build(cube, "cubes", tsp::ValueRange{0, 1}), flat_tf(c), tsp::CachePolicy::on);
  auto camera = [](const Scene& sc, double az, double el, std::array<double, 3> voxel) {
    tsp::CameraParams p;
    p.azimuth_deg = az;
    p.elevation_deg = el;
    p.width = sc.ctx->width();
    p.height = sc.ctx->height();
    p.voxel_size = voxel;
    return tsp::Camera(sc.file->tree().octree().dims(), p);
  };
  auto frame = [](Scene& sc, const tsp::Camera& cam, Compositing comp, bool baseline) {
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
  const std::string path = build(src, "ramp", tsp::ValueRange{0, 1});
  tsp::TransferFunction tf({0, 1}, 8);
  for (int j = 0; j < 8; ++j) tf.set_entry(j, {j / 7.f, 1 - j / 7.f, 0.5f, 0.03f + 0.02f * j});
  Scene scene(path, tf, tsp::CachePolicy::on);
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
  const std::string path = build(*src, "plume_reuse", {}, 8);
  auto file = tsp::TspFile::open(path);
  const auto tf = tsp::preset_transfer_function("filled", file->tree().value_range());
  Scene with(path, tf, tsp::CachePolicy::on), without(path, tf, tsp::CachePolicy::on);
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
  const std::string path = build(*src, "plume_methods", {}, 8);
  auto file = tsp::TspFile::open(path);
  for (const char* preset : {"sparse", "filled"}) {
    Scene scene(path, tsp::preset_transfer_function(preset, file->tree().value_range()),
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
  const std::string path = build(*src, "shock");
  auto file = tsp::TspFile::open(path);
  for (const char* preset : {"sparse", "filled"}) {
    Scene scene(path, tsp::preset_transfer_function(preset, file->tree().value_range()),
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
  const std::string path = build(src, "dense");
  auto file = tsp::TspFile::open(path);
  Scene scene(path, tsp::preset_transfer_function("filled", file->tree().value_range()),
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
  Scene sparse(path, tsp::preset_transfer_function("sparse", file->tree().value_range()),
               tsp::CachePolicy::on);
  RenderSettings s;
  EXPECT_FALSE(sparse.renderer->render(0, sparse.camera(30, 20), s, sparse.nodes).dense);
}

TEST(VolumeRenderer, ZeroToleranceMatchesBaselineOnRealData) {
  const fs::path nc = tsptest::shared_data_dir() / "wrf-katrina" / "ci_test_file.nc";
  if (!fs::exists(nc)) GTEST_SKIP() << nc << " not present";
  tsp::SourceOptions so;
  so.field = "QCLOUD";
  auto src = tsp::open_source(nc.string(), so);
  const std::string path = build(*src, "katrina");
  auto file = tsp::TspFile::open(path);
  Scene scene(path, tsp::preset_transfer_function("filled", file->tree().value_range()),
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
  const std::string path = build(*src, "plume");
  auto file = tsp::TspFile::open(path);
  for (const char* preset : {"sparse", "filled"}) {
    Scene scene(path, tsp::preset_transfer_function(preset, file->tree().value_range()),
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
  const std::string path = build(*src, "shock", {}, 8);
  auto file = tsp::TspFile::open(path);
  const auto tf = tsp::preset_transfer_function("filled", file->tree().value_range());
  Scene on(path, tf, tsp::CachePolicy::on), off(path, tf, tsp::CachePolicy::off);
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
  const std::string path = build(*src, "shock", {}, 8);
  auto file = tsp::TspFile::open(path);
  Scene scene(path, tsp::preset_transfer_function("filled", file->tree().value_range()),
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
  const std::string path = build(*src, "shock", {}, 8);
  auto file = tsp::TspFile::open(path);
  Scene scene(path, tsp::preset_transfer_function("sparse", file->tree().value_range()),
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
  const std::string path = build(*src, "shock", {}, 8);
  auto file = tsp::TspFile::open(path);
  const tsp::ValueRange range = file->tree().value_range();
  Scene whole(path, tsp::preset_transfer_function("sparse", range), tsp::CachePolicy::on, 80, 60,
              tsp::Metric::approximate);
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
  const std::string path = build(*src, "shock", {}, 8);
  auto file = tsp::TspFile::open(path);
  Scene scene(path, tsp::preset_transfer_function("filled", file->tree().value_range()),
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
  const std::string path = build(*src, "shock", {}, 8);
  auto file = tsp::TspFile::open(path);
  const auto tf = tsp::preset_transfer_function("filled", file->tree().value_range());
  Scene unlimited(path, tf, tsp::CachePolicy::on, 80, 60, tsp::Metric::approximate);
  Scene limited(path, tf, tsp::CachePolicy::on, 80, 60, tsp::Metric::approximate);
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

// Clip probes in the renderer (issue 14), on OSMesa: a constant cube clipped by a plane through
// its centre keeps exactly half its projected coverage and never uploads the removed half; the
// clip surface shows the TF colour of the constant; sphere, rotated box and every CSG operation
// cover exactly the pixels a per-pixel brute-force ray march finds kept (up to the silhouette's
// pixel row).
#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <string>

#include "render/volume_renderer.h"
#include "support/memory_source.h"
#include "support/paths.h"
#include "tsp/build/build.h"
#include "tsp/clip/probe.h"
#include "tsp/core/color.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {
namespace {

constexpr int kW = 120, kH = 120;

tsp::TransferFunction flat_tf(tsp::Rgba c) {
  const std::vector<tsp::TfPoint> pts = {{0.0, c}, {1.0, c}};
  return tsp::TransferFunction::from_points({0, 1}, pts);
}

struct Cube {
  std::unique_ptr<tsp::TspFile> file;
  std::unique_ptr<GlContext> ctx = create_offscreen_context(kW, kH);
  tsp::TransferFunction tf;
  tsp::MetricResult metric;
  Cube() {
    auto src = tsptest::MemorySource::from_function({33, 33, 33}, 1,
                                                    [](int, int, int, int) { return 0.5f; });
    const std::string path = (tsptest::temp_dir() / "cube.tsp").string();
    tsp::BuildOptions o;
    o.brick_size = 8;
    o.range = tsp::ValueRange{0, 1};
    tsp::build_tsp_file(src, path, o);
    file = tsp::TspFile::open(path);
    const tsp::Rgba c{0.2f, 0.6f, 0.9f, 0.08f};
    tf = flat_tf(c);
    metric = tsp::compute_errors(tsp::Metric::approximate, file->tree(), tf, nullptr, 1);
  }
  tsp::Camera camera(double az, double el) const {
    tsp::CameraParams p;
    p.azimuth_deg = az;
    p.elevation_deg = el;
    p.width = kW;
    p.height = kH;
    return tsp::Camera(file->tree().octree().dims(), p);
  }
  // A frame with the clip solid (no probes: none) and its report.
  tsp::Image frame(VolumeRenderer& r, const tsp::Camera& cam, FrameReport* report = nullptr) {
    tsp::WholeTreeMetric nodes(metric);
    RenderSettings s;
    s.reuse_image = false;
    const FrameReport rep = r.render(0, cam, s, nodes);
    if (report) *report = rep;
    return ctx->read_pixels();
  }
};

bool covered(const tsp::Image& im, int x, int y) {
  const std::uint8_t* p = im.at(x, y);
  return p[0] + p[1] + p[2] > 3;
}

double coverage(const tsp::Image& im) {
  int n = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) n += covered(im, x, y);
  return double(n) / (im.width * im.height);
}

TEST(ClipRender, APlaneThroughTheCentreKeepsHalfAndUploadsHalf) {
  Cube cube;
  VolumeRenderer r(*cube.ctx, *cube.file, tsp::CachePolicy::on);
  r.set_transfer_function(cube.tf);
  const tsp::Camera front = cube.camera(0, 0);  // along +y: x to the right
  const double whole = coverage(cube.frame(r, front));
  ASSERT_GT(whole, 0.1);
  r.clear_textures();
  r.set_clip(tsp::ClipRegion({tsp::parse_probe("plane:1,0,0,16")}, tsp::ProbeOp::intersect,
                             {0, 0, 0}, {1, 1, 1}),
             std::nullopt);
  FrameReport rep;
  const tsp::Image half = cube.frame(r, front, &rep);
  EXPECT_NEAR(coverage(half) / whole, 0.5, 0.5 * 2.0 / (whole * kW));  // within a pixel column
  // Left of the centre drawn, right of it not.
  EXPECT_TRUE(covered(half, kW / 2 - 4, kH / 2));
  EXPECT_FALSE(covered(half, kW / 2 + 4, kH / 2));
  // The bricks wholly right of the plane (a voxel of margin) are clipped: not drawn, never
  // read or uploaded; those across it are textured (the coherent cube is otherwise drawn flat)
  // and clipped per sample.
  EXPECT_GT(rep.class_percent[std::size_t(tsp::DrawClass::clipped)], 30.0);
  const tsp::Octree& o = cube.file->tree().octree();
  const tsp::ClipRegion clip = r.clip();
  int across = 0;
  for (int b = 0; b < o.brick_count(); ++b) {
    const tsp::ClipSide side = clip.classify(tsp::geometric_box(o.brick_box(b), o.dims()), 1.0);
    across += side == tsp::ClipSide::straddles;
    if (side == tsp::ClipSide::removed) {
      EXPECT_FALSE(r.brick_cache().contains(b, 0)) << "brick " << b << " was read";
    }
  }
  EXPECT_EQ(r.texture_count(), across);
}

TEST(ClipRender, TheSurfaceShowsTheTfColourOfTheConstant) {
  Cube cube;
  VolumeRenderer r(*cube.ctx, *cube.file, tsp::CachePolicy::on);
  r.set_transfer_function(cube.tf);
  // Keep y ≥ 16, the far half: the ray meets the cut face head on (normal along the view).
  const tsp::Rgba s{0.9f, 0.3f, 0.1f, 0.5f};
  const tsp::TransferFunction surface = flat_tf(s);
  r.set_clip(tsp::ClipRegion({tsp::parse_probe("plane:0,-1,0,-16")}, tsp::ProbeOp::intersect,
                             {0, 0, 0}, {1, 1, 1}),
             surface);
  const tsp::Image im = cube.frame(r, cube.camera(0, 0));
  const std::uint8_t* px = im.at(kW / 2, kH / 2);
  const tsp::Luv want = tsp::srgb8_to_luv(std::uint8_t(std::lround(255 * s.r)),
                                          std::uint8_t(std::lround(255 * s.g)),
                                          std::uint8_t(std::lround(255 * s.b)));
  EXPECT_LT(tsp::delta_e_luv(tsp::srgb8_to_luv(px[0], px[1], px[2]), want), 1.0)
      << int(px[0]) << "," << int(px[1]) << "," << int(px[2]);
}

// Per pixel: does the ray through its centre meet a kept point inside the volume box?
bool brute_force_kept(const tsp::Camera& cam, const tsp::ClipRegion& clip, int x, int y) {
  const glm::dmat4 inv = glm::inverse(cam.view_projection());
  const double nx = 2 * (x + 0.5) / kW - 1, ny = 1 - 2 * (y + 0.5) / kH;
  const glm::dvec4 a = inv * glm::dvec4(nx, ny, -1, 1), b = inv * glm::dvec4(nx, ny, 1, 1);
  const glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w;
  constexpr int kSteps = 4000;
  for (int i = 0; i <= kSteps; ++i) {
    const glm::dvec3 p = p0 + (p1 - p0) * (double(i) / kSteps);
    if (p.x < 0 || p.y < 0 || p.z < 0 || p.x > 32 || p.y > 32 || p.z > 32) continue;
    if (clip.kept({p.x, p.y, p.z})) return true;
  }
  return false;
}

TEST(ClipRender, SilhouettesOfSpheresBoxesAndCsgMatchABruteForceMarch) {
  Cube cube;
  const tsp::Camera cam = cube.camera(35, 25);
  const std::vector<std::pair<std::vector<std::string>, tsp::ProbeOp>> cases = {
      {{"sphere:16,16,16,11"}, tsp::ProbeOp::intersect},
      {{"box:16,16,16,12,7,9,20,30,40"}, tsp::ProbeOp::intersect},
      {{"sphere:12,16,16,9", "sphere:21,16,16,9"}, tsp::ProbeOp::intersect},
      {{"sphere:12,16,16,9", "sphere:21,16,16,9"}, tsp::ProbeOp::unite},
      {{"box:16,16,16,14,14,14", "sphere:16,16,30,12"}, tsp::ProbeOp::subtract}};
  for (const auto& [texts, op] : cases) {
    std::vector<tsp::Probe> probes;
    for (const std::string& t : texts) probes.push_back(tsp::parse_probe(t));
    const tsp::ClipRegion clip(probes, op, {0, 0, 0}, {1, 1, 1});
    VolumeRenderer r(*cube.ctx, *cube.file, tsp::CachePolicy::on);
    r.set_transfer_function(cube.tf);
    r.set_clip(clip, cube.tf);  // the surface on: every kept ray shows colour
    const tsp::Image im = cube.frame(r, cam);
    std::vector<int> want(kW * kH);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) want[std::size_t(y * kW + x)] = brute_force_kept(cam, clip, x, y);
    int wrong = 0, covered_n = 0;
    for (int y = 1; y < kH - 1; ++y)
      for (int x = 1; x < kW - 1; ++x) {
        const int w = want[std::size_t(y * kW + x)];
        covered_n += w;
        if (covered(im, x, y) == bool(w)) continue;
        bool edge = false;  // the silhouette's own pixel row may go either way
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) edge |= want[std::size_t((y + dy) * kW + x + dx)] != w;
        wrong += !edge;
      }
    EXPECT_GT(covered_n, 200) << texts[0];
    EXPECT_EQ(wrong, 0) << texts[0] << " " << tsp::to_string(op);
  }
}

}  // namespace
}  // namespace tspgl

// A source with a stencil through the builder: statistics, histogram and data range count inside
// voxels only, a brick wholly outside carries the empty marker (and is transparent under any
// transfer function), the inside fractions and /bricks/inside are what the stencil says.
#include <gtest/gtest.h>

#include <cmath>

#include "support/memory_source.h"
#include "support/paths.h"
#include "tsp/build/build.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/store/brick_cache.h"
#include "tsp/store/tsp_file.h"

namespace tsp {
namespace {

// 31 x 16 x 16 samples over 2 steps, bricks of 16 (2 x 1 x 1 bricks, 15 own columns each):
// inside where x < 12 (12 of brick 0's columns, none of brick 1's). Outside values are 1000.
class HalfInside final : public VolumeSource {
 public:
  explicit HalfInside(float outside = 1000.f) : outside_(outside) {}
  Dims dims() const override { return {31, 16, 16}; }
  int steps() const override { return 2; }
  std::string describe() const override { return "half inside"; }
  bool has_stencil() const override { return true; }
  std::array<double, 3> origin() const override { return {1, 2, 3}; }
  std::array<double, 3> spacing() const override { return {0.5, 0.5, 0.5}; }
  static bool in(int x) { return x < 12; }
  static float value(int x, int y, int t) { return float(x + y + 10 * t); }
  void read_step(int t, std::span<float> out) override {
    std::vector<std::uint8_t> inside(out.size());
    read_step_inside(t, out, inside);
  }
  void read_step_inside(int t, std::span<float> out, std::span<std::uint8_t> inside) override {
    const Dims d = dims();
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x) {
          const std::size_t i = std::size_t(x + d.x * (y + d.y * z));
          inside[i] = in(x);
          out[i] = in(x) ? value(x, y, t) : outside_;
        }
  }

 private:
  float outside_;
};

TEST(StencilBuild, StatisticsCountInsideVoxelsOnly) {
  HalfInside src;
  const std::string path = (tsptest::temp_dir() / "stencil.tsp").string();
  BuildOptions o;
  o.brick_size = 16;
  const BuildReport r = build_tsp_file(src, path, o);
  EXPECT_EQ(r.data_range.lo, 0);
  EXPECT_EQ(r.data_range.hi, 11 + 15 + 10);  // the largest inside value, not 1000
  auto f = TspFile::open(path);
  const TspTree& tree = f->tree();
  ASSERT_TRUE(tree.has_stencil());
  EXPECT_EQ(f->metadata().origin, (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(f->metadata().spacing, (std::array<double, 3>{0.5, 0.5, 0.5}));
  const Octree& oct = tree.octree();
  ASSERT_EQ(oct.brick_count(), 2);
  // Brick 0 owns x in [0, 15): 12 of its 15 columns inside; brick 1 none.
  const int leaf0 = oct.brick_node(0), leaf1 = oct.brick_node(1);
  EXPECT_FLOAT_EQ(tree.inside_fraction(leaf0), 12.f / 15);
  EXPECT_FLOAT_EQ(tree.inside_fraction(leaf1), 0.f);
  EXPECT_TRUE(tree.stats(tree.id(leaf1, 0)).empty());
  // The root over all steps: the mean of x + y + 10t over the inside voxels, x < 12, y < 16.
  const NodeStats& root = tree.stats(tree.id(0, 0));
  EXPECT_FALSE(root.empty());
  EXPECT_NEAR(root.mean, 5.5 + 7.5 + 5, 1e-9);
  EXPECT_EQ(root.max, 11 + 15 + 10);
  std::uint64_t counted = 0;
  for (std::uint64_t h : f->metadata().histogram) counted += h;
  EXPECT_EQ(counted, 12u * 16 * 16 * 2);
  // The empty brick is transparent under a fully opaque transfer function.
  const Rgba c{1, 1, 1, 1};
  std::vector<TfPoint> pts = {{0.0, c}, {1.0, c}};
  const TransferFunction tf = TransferFunction::from_points({0, 1000}, pts);
  const MetricResult m = compute_errors(Metric::scalar, tree, tf, f.get(), 1);
  EXPECT_TRUE(m.transparent[std::size_t(tree.id(leaf1, 0))]);
  EXPECT_FALSE(m.transparent[std::size_t(tree.id(leaf0, 0))]);
  // The cached brick carries its flags after its codes: brick 0's sample x = 11 in, 12 out.
  BrickCache cache(*f, 1 << 20);
  BrickSamples b0 = cache.get(0, 1);
  const std::size_t n = std::size_t(oct.lattice(0).count());
  ASSERT_EQ(b0->size(), 2 * n);
  EXPECT_EQ((*b0)[n + 11], 1);
  EXPECT_EQ((*b0)[n + 12], 0);
}

TEST(StencilBuild, TheReferenceMetricIgnoresWhatLiesOutside) {
  // Two files that differ only in the padding outside the stencil: every node's reference
  // errors agree (the metric reads the stencil and skips outside samples, as the builder does).
  std::vector<MetricResult> results;
  for (float outside : {1000.f, -50.f}) {
    HalfInside src(outside);
    const std::string path =
        (tsptest::temp_dir() / ("ref_" + std::to_string(int(outside)) + ".tsp")).string();
    BuildOptions o;
    o.brick_size = 16;
    o.range = ValueRange{-100, 1100};
    build_tsp_file(src, path, o);
    auto f = TspFile::open(path);
    std::vector<TfPoint> pts = {{0.0, Rgba{0, 0, 1, 0.5f}}, {1.0, Rgba{1, 0, 0, 0.5f}}};
    const TransferFunction tf = TransferFunction::from_points({-100, 1100}, pts);
    results.push_back(compute_errors(Metric::reference, f->tree(), tf, f.get(), 1));
  }
  ASSERT_EQ(results[0].errors.spatial.size(), results[1].errors.spatial.size());
  for (std::size_t i = 0; i < results[0].errors.spatial.size(); ++i) {
    EXPECT_FLOAT_EQ(results[0].errors.spatial[i], results[1].errors.spatial[i]) << i;
    EXPECT_FLOAT_EQ(results[0].errors.temporal[i], results[1].errors.temporal[i]) << i;
  }
}

}  // namespace
}  // namespace tsp

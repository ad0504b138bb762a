// span_mean against brute force: the rounded per-voxel mean of the stored codes, and with a
// moving stencil, the middle step's flags and each voxel's mean over the steps it is inside.
#include "tsp/store/span_mean.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "support/memory_tree.h"
#include "support/paths.h"
#include "tsp/build/build.h"
#include "tsp/store/tsp_file.h"

namespace tsp {
namespace {

using tsptest::MemoryBrickStore;
using tsptest::MemorySeries;

std::vector<std::uint16_t> direct(const BrickStore& store, int brick, int step) {
  std::vector<std::uint16_t> v(std::size_t(store.tree().octree().lattice(brick).count()));
  store.read_brick(brick, step, v);
  return v;
}

TEST(SpanMean, IsTheRoundedMeanOfTheStepsCodes) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-3, 7);
  const MemoryBrickStore store(
      MemorySeries::generate({20, 12, 9}, 6, [&](int, int, int, int) { return u(rng); }), 8);
  BrickCache cache(store, 1 << 22);
  for (int b = 0; b < store.tree().octree().brick_count(); ++b) {
    for (const auto& [t0, t1] : {std::pair{0, 5}, std::pair{1, 3}, std::pair{2, 3}}) {
      const BrickSamples m = span_mean(cache, b, t0, t1);
      std::vector<std::vector<std::uint16_t>> steps;
      for (int t = t0; t <= t1; ++t) steps.push_back(direct(store, b, t));
      ASSERT_EQ(m->size(), steps[0].size());
      const std::uint64_t n = std::uint64_t(t1 - t0 + 1);
      for (std::size_t i = 0; i < m->size(); ++i) {
        std::uint64_t sum = 0;
        for (const auto& s : steps) sum += s[i];
        ASSERT_EQ((*m)[i], std::uint16_t((sum + n / 2) / n)) << "brick " << b << " sample " << i;
      }
    }
    // One step: the cache's own samples.
    EXPECT_EQ(span_mean(cache, b, 4, 4), cache.get(b, 4));
  }
}

// 16³ samples, 3 steps, one brick: voxel x is inside from step x % 3 on (so x % 3 == 0 always,
// x % 3 == 2 only at the last step); the value is x + 100·t inside and 5000 outside.
class Arriving final : public VolumeSource {
 public:
  Dims dims() const override { return {16, 16, 16}; }
  int steps() const override { return 3; }
  std::string describe() const override { return "arriving"; }
  bool has_stencil() const override { return true; }
  static bool in(int x, int t) { return t >= x % 3; }
  void read_step(int t, std::span<float> out) override {
    std::vector<std::uint8_t> inside(out.size());
    read_step_inside(t, out, inside);
  }
  void read_step_inside(int t, std::span<float> out, std::span<std::uint8_t> inside) override {
    for (int z = 0; z < 16; ++z)
      for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
          const std::size_t i = std::size_t(x + 16 * (y + 16 * z));
          inside[i] = in(x, t);
          out[i] = in(x, t) ? float(x + 100 * t) : 5000.f;
        }
  }
};

TEST(SpanMean, WithAStencilAveragesInsideStepsAndKeepsTheMiddleFlags) {
  Arriving src;
  const std::string path = (tsptest::temp_dir() / "arriving.tsp").string();
  BuildOptions o;
  o.brick_size = 16;
  build_tsp_file(src, path, o);
  auto f = TspFile::open(path);
  ASSERT_TRUE(f->tree().has_stencil());
  ASSERT_EQ(f->tree().octree().brick_count(), 1);
  BrickCache cache(*f, 1 << 22);
  // Each step's codes, then its flags, read through a cache of its own.
  BrickCache plain(*f, 1 << 22);
  const std::vector<std::vector<std::uint16_t>> steps = {*plain.get(0, 0), *plain.get(0, 1),
                                                         *plain.get(0, 2)};
  const BrickSamples m = span_mean(cache, 0, 0, 2);
  const std::size_t n = steps[0].size() / 2;
  ASSERT_EQ(m->size(), 2 * n);
  const Box box = f->tree().octree().brick_samples(0);
  ASSERT_EQ(box.count(), std::int64_t(n));
  int checked = 0;
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ((*m)[n + i], steps[1][n + i]) << i;  // the middle step's flag
    std::uint64_t sum = 0, count = 0;
    for (const auto& s : steps)
      if (s[n + i] != 0) sum += s[i], ++count;
    if (count == 0) continue;
    EXPECT_EQ((*m)[i], std::uint16_t((sum + count / 2) / count)) << i;
    ++checked;
  }
  EXPECT_GT(checked, int(n / 2));
}

}  // namespace
}  // namespace tsp

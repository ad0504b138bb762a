#include "tsp/frame/sample_steps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace tsp {
namespace {

// A ramp over [0, 1]: colour and opacity rise with the value.
TransferFunction ramp_tf() {
  const std::vector<TfPoint> pts{{0.0, {0, 0, 1, 0}}, {1.0, {1, 0.5f, 0, 0.8f}}};
  return TransferFunction::from_points({0, 1}, pts, 64);
}

// The premultiplied colour a code maps to, by the TF's own lookup of its value.
std::array<float, 4> colour_of(const TransferFunction& tf, ValueRange q, std::uint16_t code) {
  const Rgba& e = tf.lookup(q.lo + double(code) / 65535.0 * q.width());
  return {e.r * e.a, e.g * e.a, e.b * e.a, e.a};
}

// Brute force: for every pair of axis neighbours in box, the change credited to the lower
// sample's cell, in a map over the whole step grid of dims.
std::vector<float> brute_cells(const TransferFunction& tf, ValueRange q,
                               const std::vector<std::uint16_t>& c, const Box& box, Dims dims) {
  const auto g = step_grid(dims);
  std::vector<float> out(std::size_t(g[0]) * g[1] * g[2], 0.f);
  auto at = [&](int x, int y, int z) {
    return c[std::size_t(((z - box.lo[2]) * box.size(1) + (y - box.lo[1])) * box.size(0) + x - box.lo[0])];
  };
  for (int z = box.lo[2]; z < box.hi[2]; ++z)
    for (int y = box.lo[1]; y < box.hi[1]; ++y)
      for (int x = box.lo[0]; x < box.hi[0]; ++x)
        for (int a = 0; a < 3; ++a) {
          int p[3] = {x, y, z};
          if (++p[a] >= box.hi[std::size_t(a)]) continue;
          const auto s = colour_of(tf, q, at(x, y, z)), t = colour_of(tf, q, at(p[0], p[1], p[2]));
          float& cell = out[std::size_t(((z / kStepCell) * g[1] + y / kStepCell) * g[0] + x / kStepCell)];
          for (int k = 0; k < 4; ++k)
            cell = std::max(cell, std::abs(s[std::size_t(k)] - t[std::size_t(k)]));
        }
  return out;
}

// c's cells placed into a map over the whole step grid of dims.
std::vector<float> placed(const CellVariations& c, Dims dims) {
  const auto g = step_grid(dims);
  std::vector<float> out(std::size_t(g[0]) * g[1] * g[2], 0.f);
  for (int z = 0; z < c.count[2]; ++z)
    for (int y = 0; y < c.count[1]; ++y)
      for (int x = 0; x < c.count[0]; ++x)
        out[std::size_t(((z + c.first[2]) * g[1] + y + c.first[1]) * g[0] + x + c.first[0])] =
            c.v[std::size_t((z * c.count[1] + y) * c.count[0] + x)];
  return out;
}

TEST(SampleSteps, StepGridCoversEverySample) {
  EXPECT_EQ(step_grid({64, 65, 1}), (std::array<int, 3>{16, 17, 1}));
  EXPECT_EQ(step_grid({4, 5, 8}), (std::array<int, 3>{1, 2, 2}));
}

TEST(SampleVariation, UniformBrickDoesNotChange) {
  const SampleVariation sv(ramp_tf(), {0, 1});
  const Box box{{3, 0, 8}, {11, 5, 12}};
  const std::vector<std::uint16_t> codes(std::size_t(box.count()), 30000);
  const CellVariations c = sv.cells(codes.data(), box);
  EXPECT_EQ(c.first, (std::array<int, 3>{0, 0, 2}));
  EXPECT_EQ(c.count, (std::array<int, 3>{3, 2, 1}));
  for (float v : c.v) EXPECT_EQ(v, 0.f);
}

TEST(SampleVariation, MatchesBruteForceOnRandomBricks) {
  const TransferFunction tf = ramp_tf();
  const Dims dims{40, 33, 21};
  for (ValueRange q : {ValueRange{0, 1}, ValueRange{-0.5, 2.0}}) {
    const SampleVariation sv(tf, q);
    std::mt19937 rng(7);
    for (int trial = 0; trial < 30; ++trial) {
      Box box;
      for (int a = 0; a < 3; ++a) {
        const int n = dims[a];
        box.lo[std::size_t(a)] = int(rng() % std::uint32_t(n - 1));
        box.hi[std::size_t(a)] = box.lo[std::size_t(a)] + 1 +
                                 int(rng() % std::uint32_t(std::min(18, n - box.lo[std::size_t(a)])));
      }
      std::vector<std::uint16_t> c(std::size_t(box.count()));
      const int spread = 1 + int(rng() % 65535), base = int(rng() % 65536);
      for (auto& v : c) v = std::uint16_t(std::clamp(base + int(rng() % std::uint32_t(spread)) - spread / 2, 0, 65535));
      const CellVariations got = sv.cells(c.data(), box);
      EXPECT_EQ(placed(got, dims), brute_cells(tf, q, c, box, dims)) << "trial " << trial;
    }
  }
}

TEST(StepRows, LargestMultiplierWhoseStepStaysWithinTheToleranceAroundTheCell) {
  // A 9-cell row with one sharp cell (variation 0.1) in the middle, the rest uniform.
  const std::array<int, 3> g{9, 1, 1};
  std::vector<float> v(9, 0.f);
  v[4] = 0.1f;
  // At spacing 1, tolerance 0.35: the sharp cell itself takes m = 3 (0.1 · 3 ≤ 0.35).
  // Cell 4 ± k: a step of L voxels reaches ceil(L / 4) cells, so m = 8 (reach 2) is allowed
  // three or more cells away, m = 4 (reach 1) two away; one away, the sharp cell is within
  // reach of every step, and m = 3 (0.3 ≤ 0.35) is the largest.
  const std::vector<std::uint8_t> rows = step_rows(v, g, 1.0, 0.35);
  const double want[9] = {8, 8, 4, 3, 3, 3, 4, 8, 8};
  for (int i = 0; i < 9; ++i) EXPECT_EQ(kStepMultipliers[rows[std::size_t(i)]], want[i]) << "cell " << i;
  // A zero tolerance samples every spacing; a uniform grid takes the largest step.
  for (std::uint8_t r : step_rows(v, g, 1.0, 0.0)) EXPECT_EQ(r, 0);
  for (std::uint8_t r : step_rows(std::vector<float>(9, 0.f), g, 2.0, 1e-6))
    EXPECT_EQ(kStepMultipliers[r], 8.0);
  // Too sharp for any coarser step.
  for (std::uint8_t r : step_rows(std::vector<float>(9, 1.f), g, 1.0, 0.5)) EXPECT_EQ(r, 0);
}

TEST(StepRows, ReachFollowsTheSpacingAlongEveryAxis) {
  // A 7³ grid, the centre cell sharp, at spacing 2: a cell takes the largest m whose step
  // either keeps 0.1 · L within 0.5 or cannot reach the centre (Chebyshev distance > its
  // reach ceil(L / 4), diagonals included) — written out independently here.
  const std::array<int, 3> g{7, 7, 7};
  std::vector<float> v(343, 0.f);
  v[171] = 0.1f;  // (3, 3, 3)
  const std::vector<std::uint8_t> rows = step_rows(v, g, 2.0, 0.5);
  for (int z = 0; z < 7; ++z)
    for (int y = 0; y < 7; ++y)
      for (int x = 0; x < 7; ++x) {
        const int d = std::max({std::abs(x - 3), std::abs(y - 3), std::abs(z - 3)});
        int want = 0;
        for (int r = 1; r < int(kStepMultipliers.size()); ++r) {
          const double step = 2.0 * kStepMultipliers[std::size_t(r)];
          const int reach = int(std::ceil(step / kStepCell));
          if (d > reach || 0.1 * step <= 0.5) want = r;
        }
        EXPECT_EQ(rows[std::size_t((z * 7 + y) * 7 + x)], want) << x << "," << y << "," << z;
      }
}

}  // namespace
}  // namespace tsp

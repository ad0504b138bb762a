#include "tsp/source/procedural/generate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

#include "tsp/core/error.h"

namespace tsp {
namespace {

using Volume = std::vector<float>;

Volume read(GeneratedSource& s, int t) {
  Volume v(std::size_t(s.dims().count()));
  s.read_step(t, v);
  return v;
}

std::vector<Volume> read_all(GeneratedSource& s) {
  std::vector<Volume> out;
  for (int t = 0; t < s.steps(); ++t) out.push_back(read(s, t));
  return out;
}

float at(const Volume& v, Dims d, int i, int j, int k) {
  return v[(std::size_t(k) * d.y + j) * d.x + i];
}

// Options without designated initialisers (GCC warns about the omitted members).
GenerateOptions opts(std::optional<Dims> dims, std::optional<int> steps,
                     std::uint64_t seed = kDefaultSeed, int threads = 0) {
  GenerateOptions o;
  o.dims = dims;
  o.steps = steps;
  o.seed = seed;
  o.threads = threads;
  return o;
}

// Normalised position of sample i of n, as docs/datasets.md defines it.
double pos(int i, int n) {
  return double(i) / (n - 1);
}

TEST(Generate, ListsShockFirstThenVortexWithDescriptionsAndDefaults) {
  auto list = list_datasets();
  ASSERT_GE(list.size(), 2u);
  EXPECT_EQ(list[0].name, "shock");
  EXPECT_EQ(list[1].name, "vortex");
  for (const auto& d : list) {
    EXPECT_FALSE(d.description.empty()) << d.name;
    EXPECT_EQ(d.description.find('\n'), std::string::npos) << d.name;
  }
  EXPECT_EQ(list[0].default_dims, (Dims{64, 64, 64}));
  EXPECT_EQ(list[0].default_steps, 32);
  auto s = make_generated_source("shock");
  EXPECT_EQ(s->dims(), (Dims{64, 64, 64}));
  EXPECT_EQ(s->steps(), 32);
  EXPECT_EQ(s->name(), "shock");
  EXPECT_EQ(s->seed(), kDefaultSeed);
}

TEST(Generate, UnknownNameIsUsageErrorListingTheKnownOnes) {
  try {
    make_generated_source("shok");
    FAIL() << "no throw";
  } catch (const UsageError& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("shok"), std::string::npos) << m;
    EXPECT_NE(m.find("shock"), std::string::npos) << m;
    EXPECT_NE(m.find("vortex"), std::string::npos) << m;
  }
}

TEST(Generate, BadDimsOrStepsAreUsageErrors) {
  for (Dims d : {Dims{0, 4, 4}, Dims{4, -1, 4}, Dims{4, 4, kMaxGeneratedEdge + 1}})
    EXPECT_THROW(make_generated_source("shock", opts(d, {})), UsageError) << to_string(d);
  for (int t : {0, -2, kMaxGeneratedSteps + 1})
    EXPECT_THROW(make_generated_source("vortex", opts({}, t)), UsageError) << t;
  try {
    make_generated_source("shock", opts({}, 0));
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("steps"), std::string::npos) << e.what();
  }
  // Degenerate but valid sizes work.
  auto s = make_generated_source("shock", opts(Dims{1, 1, 1}, 1));
  EXPECT_EQ(read(*s, 0).size(), 1u);
}

TEST(Generate, DescribeNamesDatasetSeedAndSize) {
  auto s = make_generated_source("vortex", opts(Dims{8, 9, 10}, 3, 77));
  std::string d = s->describe();
  EXPECT_NE(d.find("vortex"), std::string::npos) << d;
  EXPECT_NE(d.find("77"), std::string::npos) << d;
  EXPECT_NE(d.find("8x9x10"), std::string::npos) << d;
}

class EveryDataset : public testing::TestWithParam<std::string> {};

TEST_P(EveryDataset, SameSeedIsBitIdenticalAndOtherSeedDiffers) {
  const GenerateOptions opt = opts(Dims{24, 20, 22}, 6, 5);
  auto a = make_generated_source(GetParam(), opt);
  auto b = make_generated_source(GetParam(), opt);
  GenerateOptions other = opt;
  other.seed = 6;
  auto c = make_generated_source(GetParam(), other);
  for (int t : {5, 0, 3}) {  // out of order: no hidden state between reads
    Volume va = read(*a, t), vb = read(*b, t), vc = read(*c, t);
    EXPECT_EQ(0, std::memcmp(va.data(), vb.data(), va.size() * sizeof(float))) << "t=" << t;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < va.size(); ++i) differ += va[i] != vc[i];
    EXPECT_GT(differ, va.size() / 20) << "t=" << t;
  }
}

TEST_P(EveryDataset, ThreadCountDoesNotChangeAnyBit) {
  Volume ref;
  for (int threads : {1, 2, 3, 7, 40}) {
    auto s = make_generated_source(GetParam(), opts(Dims{19, 17, 13}, 4, 9, threads));
    Volume v = read(*s, 2);
    if (ref.empty()) ref = v;
    EXPECT_EQ(0, std::memcmp(ref.data(), v.data(), v.size() * sizeof(float)))
        << threads << " threads";
  }
}

TEST_P(EveryDataset, ValuesAreFinite) {
  auto s = make_generated_source(GetParam(), opts(Dims{32, 32, 32}, 4));
  for (int t = 0; t < 4; ++t)
    for (float v : read(*s, t)) ASSERT_TRUE(std::isfinite(v));
}

// Grids 17 and 65 samples wide share every 4th sample position exactly (i/16 = 4i/64); so do
// 5 and 17 steps. The field there must agree: it depends on dims only via the position.
TEST_P(EveryDataset, CoarseGridSamplesMatchFineGridAtTheSamePositions) {
  auto coarse = make_generated_source(GetParam(), opts(Dims{17, 17, 17}, 5));
  auto fine = make_generated_source(GetParam(), opts(Dims{65, 65, 65}, 17));
  const Dims dc = coarse->dims(), df = fine->dims();
  for (int t : {0, 2, 4}) {
    Volume c = read(*coarse, t), f = read(*fine, 4 * t);
    double max_diff = 0;
    int nonzero = 0;
    for (int k = 0; k < dc.z; ++k)
      for (int j = 0; j < dc.y; ++j)
        for (int i = 0; i < dc.x; ++i) {
          float a = at(c, dc, i, j, k), b = at(f, df, 4 * i, 4 * j, 4 * k);
          max_diff = std::max(max_diff, double(std::fabs(a - b)));
          nonzero += a != 0;
        }
    EXPECT_LT(max_diff, 1e-4) << "t=" << t;
    EXPECT_GT(nonzero, 50) << "t=" << t;  // the comparison saw real structure
  }
}

INSTANTIATE_TEST_SUITE_P(Datasets, EveryDataset, testing::Values("shock", "vortex"));

// ---- shock: the structural promises of docs/datasets.md ------------------------------------

class Shock : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto s = make_generated_source("shock", opts(kDims, kSteps));
    steps_ = new std::vector<Volume>(read_all(*s));
  }
  static void TearDownTestSuite() { delete steps_; }
  static const Volume& step(int t) { return (*steps_)[t]; }
  static constexpr Dims kDims{48, 48, 48};
  static constexpr int kSteps = 16;
  static std::vector<Volume>* steps_;
};
std::vector<Volume>* Shock::steps_ = nullptr;

TEST_F(Shock, GasAheadOfTheFrontIsExactlyZeroAtEveryStep) {
  // Documented: gas with x > 0.9 above the ground (z > 0.28) is never reached by the front.
  const Dims d = kDims;
  int region = 0;
  for (int t = 0; t < kSteps; ++t)
    for (int k = 0; k < d.z; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i) {
          if (pos(i, d.x) <= 0.9 || pos(k, d.z) <= 0.28) continue;
          ASSERT_EQ(at(step(t), d, i, j, k), 0.0f) << i << "," << j << "," << k << " t=" << t;
          region += t == 0;
        }
  EXPECT_GT(region, d.count() / 20);
  // At the first step most of the box is still empty.
  const auto zeros = std::count(step(0).begin(), step(0).end(), 0.0f);
  EXPECT_GT(zeros, d.count() / 2);
}

TEST_F(Shock, PillarAndGroundAreExactlyConstantOverAllSteps) {
  const Dims d = kDims;
  std::int64_t constant_nonzero = 0;
  for (std::int64_t v = 0; v < d.count(); ++v) {
    bool same = true;
    for (int t = 1; t < kSteps && same; ++t) same = step(t)[v] == step(0)[v];
    constant_nonzero += same && step(0)[v] != 0;
  }
  // Pillar (radius 0.1, height 0.6) and ground (≥ 0.2 deep) together fill > 20% of the box.
  EXPECT_GT(constant_nonzero, d.count() * 20 / 100);
  // The pillar's axis holds the documented value 0.4; the bottom layer is ground everywhere.
  const int pi = int(std::lround(0.55 * (d.x - 1))), pj = int(std::lround(0.42 * (d.y - 1)));
  for (int t = 0; t < kSteps; ++t) {
    for (int k = 0; pos(k, d.z) < 0.6; ++k) EXPECT_EQ(at(step(t), d, pi, pj, k), 0.4f) << k;
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const double rx = pos(i, d.x) - 0.55, ry = pos(j, d.y) - 0.42;
        if (rx * rx + ry * ry < 0.11 * 0.11) continue;  // the pillar stands on the ground
        float g = at(step(t), d, i, j, 0);
        ASSERT_EQ(g, at(step(0), d, i, j, 0));
        ASSERT_GE(g, 0.18f);  // documented ground range [0.18, 0.30]
        ASSERT_LE(g, 0.30f);
      }
  }
}

// The front on row (j, k): the last voxel along x that is not 0. Behind it nothing is 0.
int front_index(const Volume& v, Dims d, int j, int k) {
  int f = -1;
  for (int i = 0; i < d.x; ++i)
    if (at(v, d, i, j, k) != 0) f = i;
  for (int i = 0; i <= f; ++i) EXPECT_NE(at(v, d, i, j, k), 0.0f) << i << "," << j << "," << k;
  return f;
}

TEST_F(Shock, FrontMovesMonotonicallyInPlusX) {
  const Dims d = kDims;
  std::vector<double> mean(kSteps, 0.0);
  int rows = 0;
  for (int k = d.z / 3; k < d.z; k += 5)  // above ground and pillar: pure gas rows
    for (int j = 0; j < d.y; j += 5) {
      if (pos(k, d.z) <= 0.6) continue;
      ++rows;
      int prev = -2;
      for (int t = 0; t < kSteps; ++t) {
        int f = front_index(step(t), d, j, k);
        EXPECT_GE(f, prev) << "row " << j << "," << k << " t=" << t;
        prev = f;
        mean[t] += f;
      }
    }
  ASSERT_GT(rows, 20);
  for (int t = 1; t < kSteps; ++t) EXPECT_GT(mean[t], mean[t - 1]) << "t=" << t;
  // Documented front: x_f = 0.08 + 0.72·τ − 0.6·((y − 0.5)² + (z − 0.55)²) ± 0.03 (ripple).
  const int jc = d.y / 2, kc = int(std::lround(0.75 * (d.z - 1)));
  const double r2 = std::pow(pos(jc, d.y) - 0.5, 2) + std::pow(pos(kc, d.z) - 0.55, 2);
  for (int t : {0, kSteps / 2, kSteps - 1}) {
    double expect = 0.08 + 0.72 * double(t) / (kSteps - 1) - 0.6 * r2;
    EXPECT_NEAR(pos(front_index(step(t), d, jc, kc), d.x), expect, 0.03 + 1.0 / (d.x - 1));
  }
}

TEST_F(Shock, WakeHasSmallScaleDetailAndEvolvesSmoothly) {
  // Along x on gas rows, well behind the front (x_f − x > 0.15): the second difference carries
  // real energy. A smooth profile (the exponentials alone) would give |Δ²v| / |v − v̄| below
  // (Δx / 0.3)² ≈ 0.005 here.
  const Dims d = kDims;
  const int t = kSteps - 1;
  double d2 = 0, var = 0, sum = 0;
  int n = 0;
  for (int k = int(0.65 * d.z); k < d.z; k += 2)
    for (int j = 0; j < d.y; j += 2) {
      int f = front_index(step(t), d, j, k);
      for (int i = 1; pos(i + 1, d.x) < pos(f, d.x) - 0.15; ++i) {
        float a = at(step(t), d, i - 1, j, k), b = at(step(t), d, i, j, k),
              c = at(step(t), d, i + 1, j, k);
        d2 += (a - 2 * b + c) * (a - 2 * b + c);
        sum += b;
        var += b * b;
        ++n;
      }
    }
  ASSERT_GT(n, 1000);
  const double mean = sum / n, sd = std::sqrt(var / n - mean * mean);
  EXPECT_GT(std::sqrt(d2 / n) / sd, 0.1);  // 0.37 here; 20× the smooth bound

  // Evolution: consecutive steps differ by less than steps far apart, yet do differ.
  auto mean_abs_diff = [&](int a, int b) {
    double s = 0;
    int m = 0;
    for (std::size_t v = 0; v < step(a).size(); ++v)
      if (step(a)[v] != 0 && step(b)[v] != 0 && step(a)[v] != step(b)[v]) {
        s += std::fabs(step(a)[v] - step(b)[v]);
        ++m;
      }
    return std::pair{m == 0 ? 0.0 : s / m, m};
  };
  auto [near, near_count] = mean_abs_diff(kSteps - 2, kSteps - 1);
  auto [far, far_count] = mean_abs_diff(kSteps / 2, kSteps - 1);
  EXPECT_GT(near_count, d.count() / 10);
  EXPECT_LT(near, 0.7 * far);
}

// ---- vortex ------------------------------------------------------------------------------------

TEST(Vortex, SignedMostlyEmptyAndNothingStatic) {
  auto s = make_generated_source("vortex", opts(Dims{40, 40, 40}, 8));
  auto all = read_all(*s);
  float lo = 0, hi = 0;
  std::int64_t zeros0 = 0;
  for (float v : all[0]) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    zeros0 += v == 0;
  }
  EXPECT_LT(lo, -0.2f);
  EXPECT_GT(hi, 0.2f);
  EXPECT_GT(zeros0, s->dims().count() / 2);
  EXPECT_LT(zeros0, s->dims().count());
  // No voxel that is non-zero at some step keeps one value over all steps.
  std::int64_t static_nonzero = 0;
  for (std::size_t v = 0; v < all[0].size(); ++v) {
    bool same = true, nonzero = all[0][v] != 0;
    for (int t = 1; t < s->steps(); ++t) {
      same = same && all[t][v] == all[0][v];
      nonzero = nonzero || all[t][v] != 0;
    }
    static_nonzero += same && nonzero;
  }
  EXPECT_EQ(static_nonzero, 0);
}

}  // namespace
}  // namespace tsp

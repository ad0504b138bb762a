// build_tsp_file: every TSP node's statistics against a brute-force double computation over the
// node's own voxels and span, plus the NaN/Inf rule, --range clamping and the histogram.
#include "tsp/build/build.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "support/memory_source.h"
#include "support/paths.h"
#include "support/tsp_compare.h"
#include "tsp/core/error.h"
#include "tsp/store/tsp_file.h"

namespace tsp {
namespace {

using tsptest::MemorySource;

// The NaN/Inf rule and clamping, as the spec and build.h state them.
double stored_value(float v, ValueRange r) {
  if (std::isnan(v)) return float(r.lo);
  return std::clamp(v, float(r.lo), float(r.hi));
}

struct Expected {
  double mean, std, min, max, e_ss, e_st;
};

// Direct two-pass formulas over the node's own voxels and span (spec §2).
Expected brute_force(const MemorySource& src, const Box& box, Span span, ValueRange r) {
  const double W = r.width();
  double sum = 0, n = 0, lo = INFINITY, hi = -INFINITY;
  for (int t = span.t0; t <= span.t1; ++t)
    for (int z = box.lo[2]; z < box.hi[2]; ++z)
      for (int y = box.lo[1]; y < box.hi[1]; ++y)
        for (int x = box.lo[0]; x < box.hi[0]; ++x) {
          double v = stored_value(src.at(x, y, z, t), r);
          sum += v;
          n += 1;
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
  const double mean = sum / n;
  double ss = 0, cov_sum = 0;
  const int m = span.length();
  for (int z = box.lo[2]; z < box.hi[2]; ++z)
    for (int y = box.lo[1]; y < box.hi[1]; ++y)
      for (int x = box.lo[0]; x < box.hi[0]; ++x) {
        double vs = 0;
        for (int t = span.t0; t <= span.t1; ++t) vs += stored_value(src.at(x, y, z, t), r);
        const double vm = vs / m;
        double vss = 0;
        for (int t = span.t0; t <= span.t1; ++t) {
          double v = stored_value(src.at(x, y, z, t), r);
          ss += (v - mean) * (v - mean);
          vss += (v - vm) * (v - vm);
        }
        cov_sum += coefficient_of_variation(std::sqrt(vss / m), vm, W);
      }
  const double sd = std::sqrt(ss / n);
  return {mean, sd, lo, hi, coefficient_of_variation(sd, mean, W), cov_sum / double(box.count())};
}

// Builds src with the given options and returns the opened file.
std::unique_ptr<TspFile> build(MemorySource& src, BuildOptions opt, BuildReport* report = nullptr) {
  auto path = (tsptest::temp_dir() / "out.tsp").string();
  BuildReport r = build_tsp_file(src, path, opt);
  if (report) *report = r;
  return TspFile::open(path);
}

// Every TSP node of the file against brute force; `scale` sets the absolute tolerance.
void check_all_nodes(const MemorySource& src, const TspTree& tree, double scale) {
  const ValueRange r = tree.value_range();
  for (int id = 0; id < tree.size(); ++id) {
    const int o = tree.octree_of(id), t = tree.time_of(id);
    const Expected e = brute_force(src, tree.octree().node(o).box, tree.time().span(t), r);
    const NodeStats& s = tree.stats(id);
    const double tol = 1e-9 * scale;
    SCOPED_TRACE("node " + std::to_string(id) + " octree " + std::to_string(o) + " time " +
                 std::to_string(t));
    ASSERT_NEAR(s.mean, e.mean, tol);
    ASSERT_NEAR(s.std, e.std, tol);
    ASSERT_EQ(s.min, float(e.min));
    ASSERT_EQ(s.max, float(e.max));
    ASSERT_NEAR(s.spatial_error, e.e_ss, 1e-6 * std::max(1.0, e.e_ss));
    ASSERT_NEAR(s.temporal_error, e.e_st, 1e-6 * std::max(1.0, e.e_st));
  }
}

MemorySource random_source(Dims d, int steps, float lo, float hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(lo, hi);
  return MemorySource::from_function(d, steps, [&](int, int, int, int) { return u(rng); });
}

class BuildStats : public ::testing::TestWithParam<int> {};

TEST_P(BuildStats, RandomThinGridMatchesBruteForce) {
  MemorySource src = random_source({37, 20, 5}, 6, 0.5f, 3.0f, 7);
  BuildOptions opt;
  opt.brick_size = GetParam();
  BuildReport rep;
  auto f = build(src, opt, &rep);
  EXPECT_EQ(src.reads(), 6);  // one pass over the input
  EXPECT_EQ(rep.source_bytes, 37 * 20 * 5 * 6 * 4);
  check_all_nodes(src, f->tree(), 3.0);
}

TEST_P(BuildStats, StructuredFieldMatchesBruteForce) {
  MemorySource src = MemorySource::from_function(
      {33, 17, 9}, 5, [](int x, int y, int z, int t) { return float(x + 2 * y - 3 * z + 10 * t); });
  BuildOptions opt;
  opt.brick_size = GetParam();
  auto f = build(src, opt);
  check_all_nodes(src, f->tree(), 100.0);
}

INSTANTIATE_TEST_SUITE_P(BrickSizes, BuildStats, ::testing::Values(4, 8, 32));

// A series long enough (1100 steps: 2199 time nodes) for the depth-first statistics pass that
// bounds memory: every node still matches brute force.
TEST(Build, LongSeriesDepthFirstPassMatchesBruteForce) {
  MemorySource src = random_source({7, 5, 4}, 1100, -2.0f, 5.0f, 11);
  BuildOptions opt;
  opt.brick_size = 4;
  auto f = build(src, opt);
  check_all_nodes(src, f->tree(), 5.0);
}

TEST(Build, LargeOffsetKeepsTheVariance) {
  // Σv² − (Σv)²/N in float would lose every digit of this variance.
  MemorySource src = random_source({20, 20, 20}, 4, 1e6f, 1e6f + 8.f, 3);
  BuildOptions opt;
  opt.brick_size = 8;
  auto f = build(src, opt);
  check_all_nodes(src, f->tree(), 1e6);
  EXPECT_GT(f->tree().stats(0).std, 1.0);
}

TEST(Build, ThreadCountDoesNotChangeTheResult) {
  MemorySource src = random_source({30, 25, 12}, 5, -1.f, 4.f, 11);
  BuildOptions one, three;
  one.brick_size = three.brick_size = 8;
  one.threads = 1;
  three.threads = 3;
  auto a = build(src, one), b = build(src, three);
  for (int id = 0; id < a->tree().size(); ++id) {
    const NodeStats &x = a->tree().stats(id), &y = b->tree().stats(id);
    ASSERT_EQ(x.mean, y.mean);
    ASSERT_EQ(x.std, y.std);
    ASSERT_EQ(x.temporal_error, y.temporal_error);
  }
  EXPECT_EQ(a->metadata().histogram, b->metadata().histogram);
}

// --compress: every brick and statistic as without it; the file smaller (a smooth field with
// constant regions); a level outside 1..9 refused before any work.
TEST(Build, DeflateKeepsEveryBrickAndShrinksTheFile) {
  MemorySource src = MemorySource::from_function({40, 33, 21}, 4, [](int x, int y, int z, int t) {
    return x < 20 ? 1.f : float(std::sin(0.2 * x + 0.1 * y * t) + 0.05 * z);
  });
  const std::filesystem::path dir = tsptest::temp_dir();
  BuildOptions plain, packed;
  plain.brick_size = packed.brick_size = 8;
  packed.deflate = 6;
  build_tsp_file(src, (dir / "plain.tsp").string(), plain);
  build_tsp_file(src, (dir / "packed.tsp").string(), packed);
  tsptest::expect_same_build(dir / "plain.tsp", dir / "packed.tsp", 1);
  EXPECT_LT(std::filesystem::file_size(dir / "packed.tsp") * 2,
            std::filesystem::file_size(dir / "plain.tsp"));
  BuildOptions bad;
  bad.deflate = 10;
  EXPECT_THROW(build_tsp_file(src, (dir / "bad.tsp").string(), bad), tsp::UsageError);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.tsp"));
}

// Pass 1 reading slabs (a source that reads part of a step) writes the same file, bit for bit,
// as reading whole steps: leaf bricks, level bricks and their residuals, with a --range clamp
// and non-finite voxels, on a grid whose bricks span several slabs and whose levels go 3 deep.
TEST(Build, SlabReadsWriteTheFileWholeStepsWrite) {
  MemorySource src = MemorySource::from_function({37, 30, 75}, 3, [](int x, int y, int z, int t) {
    if (x == 3 && y == 4 && z == 50) return t == 1 ? NAN : INFINITY;
    return float(std::sin(0.3 * x + 0.2 * y * (t + 1)) + 0.02 * z);
  });
  const std::filesystem::path dir = tsptest::temp_dir();
  BuildOptions o;
  o.brick_size = 8;
  o.range = ValueRange{-0.9, 2.0};
  build_tsp_file(src, (dir / "whole.tsp").string(), o);
  EXPECT_EQ(src.slab_reads(), 0);
  src.set_reads_slabs(true);
  build_tsp_file(src, (dir / "slabs.tsp").string(), o);
  EXPECT_EQ(src.slab_reads(), 3 * 75);  // a quarter of a layer of 7 cells: slabs of one plane
  tsptest::expect_same_build(dir / "whole.tsp", dir / "slabs.tsp", 1);
  auto f = TspFile::open((dir / "slabs.tsp").string());
  EXPECT_GE(f->tree().octree().level_brick_count(), 9);
}

TEST(Build, SingleVoxelSingleStep) {
  MemorySource src({1, 1, 1}, {{2.5f}});
  auto f = build(src, {});
  ASSERT_EQ(f->tree().size(), 1);
  const NodeStats& s = f->tree().stats(0);
  EXPECT_EQ(s.mean, 2.5);
  EXPECT_EQ(s.std, 0);
  EXPECT_EQ(s.min, 2.5f);
  EXPECT_EQ(s.spatial_error, 0);
  EXPECT_EQ(s.temporal_error, 0);
}

TEST(BuildCov, ZeroFieldHasZeroErrors) {
  MemorySource src =
      MemorySource::from_function({10, 9, 7}, 3, [](int, int, int, int) { return 0.f; });
  BuildOptions opt;
  opt.brick_size = 4;
  BuildReport rep;
  auto f = build(src, opt, &rep);
  EXPECT_EQ(rep.data_range, (ValueRange{0, 0}));
  for (const NodeStats& s : f->tree().all_stats()) {
    EXPECT_EQ(s.mean, 0);
    EXPECT_EQ(s.std, 0);
    EXPECT_EQ(s.spatial_error, 0);
    EXPECT_EQ(s.temporal_error, 0);
  }
}

TEST(BuildCov, ZeroMeanDividesByTheRangeWidth) {
  // Every voxel alternates +a, −a: spans of two or four steps have mean exactly 0 and σ = a;
  // the COV rule then divides by the range width 2a, so both errors are exactly 1/2.
  const float a = 1.5f;
  MemorySource src = MemorySource::from_function(
      {9, 6, 5}, 4, [&](int, int, int, int t) { return t % 2 ? -a : a; });
  BuildOptions opt;
  opt.brick_size = 4;
  auto f = build(src, opt);
  const TspTree& tree = f->tree();
  for (int id = 0; id < tree.size(); ++id) {
    const NodeStats& s = tree.stats(id);
    if (tree.time().is_leaf(tree.time_of(id))) {
      EXPECT_EQ(s.spatial_error, 0);
      EXPECT_EQ(s.temporal_error, 0);
    } else {
      EXPECT_EQ(s.mean, 0);
      EXPECT_FLOAT_EQ(s.spatial_error, 0.5f);
      EXPECT_FLOAT_EQ(s.temporal_error, 0.5f);
    }
  }
  check_all_nodes(src, tree, 2.0);
}

TEST(BuildCov, NegativeFieldUsesAbsoluteMean) {
  MemorySource src = MemorySource::from_function(
      {12, 11, 6}, 4, [](int x, int y, int z, int t) { return -1.f - x - 0.5f * y * (t + 1) - z; });
  BuildOptions opt;
  opt.brick_size = 4;
  auto f = build(src, opt);
  check_all_nodes(src, f->tree(), 50.0);
  EXPECT_GT(f->tree().stats(0).spatial_error, 0);
  EXPECT_GT(f->tree().stats(0).temporal_error, 0);
}

TEST(Build, NanAndInfFollowTheRule) {
  MemorySource src = random_source({11, 10, 9}, 3, 1.f, 2.f, 5);
  auto data = std::vector<std::vector<float>>(3);
  for (int t = 0; t < 3; ++t)
    for (int z = 0; z < 9; ++z)
      for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 11; ++x) data[t].push_back(src.at(x, y, z, t));
  data[0][5] = NAN;
  data[1][300] = INFINITY;
  data[2][900] = -INFINITY;
  data[2][901] = NAN;
  MemorySource bad({11, 10, 9}, data);
  BuildOptions opt;
  opt.brick_size = 4;
  BuildReport rep;
  auto f = build(bad, opt, &rep);
  EXPECT_EQ(rep.nonfinite_count, 4);
  EXPECT_EQ(f->metadata().nonfinite_count, 4);
  // The finite range ignores them, and they are replaced inside it.
  EXPECT_GE(rep.data_range.lo, 1.0);
  EXPECT_LE(rep.data_range.hi, 2.0);
  EXPECT_EQ(f->tree().value_range(), rep.data_range);
  check_all_nodes(bad, f->tree(), 2.0);
  EXPECT_EQ(f->tree().stats(0).min, float(rep.data_range.lo));
  EXPECT_EQ(f->tree().stats(0).max, float(rep.data_range.hi));
}

TEST(Build, RangeClampsSamplesAndStatistics) {
  MemorySource src = random_source({14, 13, 6}, 4, -2.f, 6.f, 9);
  BuildOptions opt;
  opt.brick_size = 8;
  opt.range = ValueRange{0.0, 4.0};
  BuildReport rep;
  auto f = build(src, opt, &rep);
  EXPECT_EQ(f->tree().value_range(), (ValueRange{0.0, 4.0}));
  EXPECT_LT(f->metadata().data_range.lo, 0.0);
  EXPECT_GT(f->metadata().data_range.hi, 4.0);
  EXPECT_EQ(f->tree().stats(0).min, 0.f);
  EXPECT_EQ(f->tree().stats(0).max, 4.f);
  check_all_nodes(src, f->tree(), 4.0);
}

TEST(Build, HistogramCountsEveryOwnVoxelOnce) {
  MemorySource src = random_source({19, 8, 7}, 3, -1.f, 1.f, 2);
  BuildOptions opt;
  opt.brick_size = 4;
  opt.range = ValueRange{-0.5, 0.5};
  auto f = build(src, opt);
  std::vector<std::uint64_t> want(kHistogramBins, 0);
  for (int t = 0; t < 3; ++t)
    for (int z = 0; z < 7; ++z)
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 19; ++x) {
          double v = stored_value(src.at(x, y, z, t), opt.range.value());
          int bin = int(std::floor((v + 0.5) * kHistogramBins / 1.0));
          want[std::clamp(bin, 0, kHistogramBins - 1)]++;
        }
  EXPECT_EQ(f->metadata().histogram, want);
}

TEST(Build, RejectsBadOptions) {
  MemorySource src = random_source({5, 5, 5}, 2, 0.f, 1.f, 1);
  auto path = (tsptest::temp_dir() / "x.tsp").string();
  BuildOptions opt;
  opt.brick_size = 12;
  EXPECT_THROW(build_tsp_file(src, path, opt), UsageError);
  opt = {};
  opt.range = ValueRange{3, 3};
  EXPECT_THROW(build_tsp_file(src, path, opt), UsageError);
  opt.range = ValueRange{NAN, 3};
  EXPECT_THROW(build_tsp_file(src, path, opt), UsageError);
  opt = {};
  opt.threads = -1;
  EXPECT_THROW(build_tsp_file(src, path, opt), UsageError);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_THROW(build_tsp_file(src, (tsptest::temp_dir() / "no/such/dir.tsp").string(), {}),
               IoError);
  EXPECT_THROW(build_tsp_file(src, tsptest::temp_dir().string(), {}), IoError);
}

// Per-step bookkeeping is bounded: 100,000 steps of a 2³ grid build in well under the memory
// the old per-step buffers took (about 17 KB a step: 1.7 GB here), and the file opens with the
// statistics of the first and last step right.
TEST(Build, HundredThousandTinyStepsBuildInBoundedMemory) {
  constexpr int kSteps = 100000;
  std::vector<std::vector<float>> steps(kSteps, std::vector<float>(8));
  for (int t = 0; t < kSteps; ++t)
    for (int i = 0; i < 8; ++i) steps[std::size_t(t)][std::size_t(i)] = float(t % 97) + 0.125f * i;
  tsptest::MemorySource src({2, 2, 2}, std::move(steps));
  const auto path = (tsptest::temp_dir() / "long.tsp").string();
  struct rusage before {};
  getrusage(RUSAGE_SELF, &before);
  BuildOptions o;
  o.brick_size = 4;
  build_tsp_file(src, path, o);
  struct rusage after {};
  getrusage(RUSAGE_SELF, &after);
  // ru_maxrss is in KiB; the source itself holds 3.2 MB of samples plus vector overhead.
  // AddressSanitizer's shadow memory and quarantine (scripts/test-sanitizers.sh) add their own.
#if defined(__SANITIZE_ADDRESS__)
  constexpr long kLimitKiB = 800 * 1024;
#else
  constexpr long kLimitKiB = 200 * 1024;
#endif
  EXPECT_LT(after.ru_maxrss - before.ru_maxrss, kLimitKiB) << "peak RSS grew by "
                                                             << after.ru_maxrss - before.ru_maxrss
                                                             << " KiB";
  auto f = TspFile::open(path);
  const TspTree& tree = f->tree();
  ASSERT_EQ(tree.time().steps(), kSteps);
  const NodeStats& first = tree.stats(tree.id(0, tree.time().leaf_of(0)));
  const NodeStats& last = tree.stats(tree.id(0, tree.time().leaf_of(kSteps - 1)));
  EXPECT_NEAR(first.mean, 0.4375, 1e-9);
  EXPECT_NEAR(last.mean, (kSteps - 1) % 97 + 0.4375, 1e-9);
}

}  // namespace
}  // namespace tsp

namespace tsp {
namespace {

TEST(DefaultBrickSize, IsThePowerOfTwoNearestAQuarterOfTheLongestEdgeIn8To64) {
  EXPECT_EQ(default_brick_size({64, 64, 64}), 16);
  EXPECT_EQ(default_brick_size({128, 40, 20}), 32);
  EXPECT_EQ(default_brick_size({48, 48, 14}), 16);  // a quarter is 12: 16 is nearer than 8 on a log scale
  EXPECT_EQ(default_brick_size({256, 256, 256}), 64);
  EXPECT_EQ(default_brick_size({2048, 16, 16}), 64);
  EXPECT_EQ(default_brick_size({20, 20, 20}), 8);
  EXPECT_EQ(default_brick_size({2, 2, 2}), 8);
}

}  // namespace
}  // namespace tsp

// Levels placed at their heights (tsp/source/level_resample.h, wrf_heights.h): columns of
// uneven levels resampled onto a uniform vertical grid, linearly in height, per step; and WRF's
// levels at their geopotential heights, checked against PH, PHB and T read here.
#include "tsp/source/level_resample.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <vector>

#include "support/memory_source.h"
#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"
#include "tsp/source/open_source.h"

namespace tsp {
namespace {

using tsptest::error_of;
using tsptest::katrina_file;

// 3 × 2 columns of 4 levels at base + {0, 10, 30, 70} m, base = 10x + 5y (+ 3 m at step 1); the
// field is 2h + 1 + 100t at each level's height h: linear in height, so resampling is exact.
constexpr Dims kStored{3, 2, 4};
constexpr double kLayers[4] = {0, 10, 30, 70};

double height(int x, int y, int k, int t) { return 10.0 * x + 5.0 * y + kLayers[k] + 3.0 * t; }

std::unique_ptr<VolumeSource> stored(int steps = 2) {
  return std::make_unique<tsptest::MemorySource>(tsptest::MemorySource::from_function(
      kStored, steps,
      [](int x, int y, int z, int t) { return float(2 * height(x, y, z, t) + 1 + 100 * t); }));
}

LevelHeightsFn heights_of(Dims d, double (*h)(int, int, int, int)) {
  return [d, h](int t, std::span<double> out) {
    std::size_t i = 0;
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x) out[i++] = h(x, y, z, t);
  };
}

TEST(LevelResample, LinearFieldIsExactAtEachStepsHeights) {
  auto s = resample_levels(stored(), heights_of(kStored, height), {}, "test heights");
  // Step 0 spans 0 (column (0, 0)) to 95 m (column (2, 1)); the thinnest layer is 10 m: 10
  // whole planes of 9.5 m.
  ASSERT_EQ(s->dims(), (Dims{3, 2, 11}));
  EXPECT_DOUBLE_EQ(s->origin()[2], 0);
  EXPECT_DOUBLE_EQ(s->spacing()[2], 9.5);
  EXPECT_TRUE(s->has_stencil());
  EXPECT_NE(s->describe().find(", levels resampled from 4 uneven levels (test heights) to 11 at "
                               "9.5 m"),
            std::string::npos)
      << s->describe();
  for (int t = 0; t < 2; ++t) {
    std::vector<float> v(std::size_t(s->dims().count()));
    std::vector<std::uint8_t> inside(v.size());
    s->read_step_inside(t, v, inside);
    std::size_t i = 0;
    for (int j = 0; j < 11; ++j)
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x, ++i) {
          const double z = 9.5 * j, lo = height(x, y, 0, t), hi = height(x, y, 3, t);
          // Inside the column: the line through the levels; beyond it, the end level's value,
          // inside only within half a plane (4.75 m).
          const double at = std::clamp(z, lo, hi);
          EXPECT_NEAR(v[i], 2 * at + 1 + 100 * t, 1e-4) << t << " " << j << " " << x << " " << y;
          EXPECT_EQ(inside[i], z >= lo - 4.75 && z <= hi + 4.75 ? 1 : 0)
              << t << " " << j << " " << x << " " << y;
        }
  }
}

double fine_bottom(int, int, int k, int) { return k == 0 ? 0.0 : k == 1 ? 1.0 : 500.0 * k; }

// A 1 m bottom layer under 1.5 km: 1501 planes at the finest spacing, capped at 256.
TEST(LevelResample, TheFinestSpacingIsCappedAndSaysSo) {
  auto s = resample_levels(stored(1), heights_of(kStored, fine_bottom), {}, "test heights");
  EXPECT_EQ(s->dims().z, kFinestLevelsCap);
  EXPECT_DOUBLE_EQ(s->spacing()[2], 1500.0 / (kFinestLevelsCap - 1));
  EXPECT_NE(s->describe().find("to 256 at 5.9 m (capped at 256 levels: the finest layer, 1.0 m, "
                               "would need 1501)"),
            std::string::npos)
      << s->describe();
}

TEST(LevelResample, ChosenCountOrSpacing) {
  VerticalLevels count;
  count.mode = VerticalLevels::Mode::count;
  count.levels = 5;
  auto c = resample_levels(stored(), heights_of(kStored, height), count, "h");
  EXPECT_EQ(c->dims().z, 5);
  EXPECT_DOUBLE_EQ(c->spacing()[2], 95.0 / 4);
  VerticalLevels spacing;
  spacing.mode = VerticalLevels::Mode::spacing;
  spacing.spacing = 20;
  auto p = resample_levels(stored(), heights_of(kStored, height), spacing, "h");
  EXPECT_EQ(p->dims().z, 6);  // round(95 / 20) + 1: the top plane within half a plane of 95 m
  EXPECT_DOUBLE_EQ(p->spacing()[2], 20);
  spacing.spacing = 0.01;  // 9501 planes
  std::string msg =
      error_of<UsageError>([&] { resample_levels(stored(), heights_of(kStored, height), spacing, "h"); });
  EXPECT_NE(msg.find("--vertical-levels 0.01m would make 9501 levels over 95.0 m; at most 4096"),
            std::string::npos)
      << msg;
  spacing.spacing = 200;
  msg = error_of<UsageError>([&] { resample_levels(stored(), heights_of(kStored, height), spacing, "h"); });
  EXPECT_NE(msg.find("larger than the levels' whole range, 95.0 m"), std::string::npos) << msg;
}

double crossing(int x, int, int k, int) { return x == 1 && k == 2 ? 5.0 : 10.0 * k; }

TEST(LevelResample, HeightsThatDoNotIncreaseAreRefused) {
  const std::string msg = error_of<FormatError>(
      [&] { resample_levels(stored(), heights_of(kStored, crossing), {}, "h"); });
  EXPECT_NE(msg.find("column (1, 0): level 2 at 5.000000 m is not above level 1 at 10.000000 m"),
            std::string::npos)
      << msg;
}

TEST(LevelResample, ParsesTheChoice) {
  EXPECT_EQ(parse_vertical_levels("finest", "--v").mode, VerticalLevels::Mode::finest);
  EXPECT_EQ(parse_vertical_levels("native", "--v").mode, VerticalLevels::Mode::native);
  EXPECT_EQ(parse_vertical_levels("96", "--v").levels, 96);
  EXPECT_EQ(parse_vertical_levels("96", "--v").mode, VerticalLevels::Mode::count);
  EXPECT_EQ(parse_vertical_levels("2.5m", "--v").spacing, 2.5);
  EXPECT_EQ(parse_vertical_levels("2.5m", "--v").mode, VerticalLevels::Mode::spacing);
  EXPECT_EQ(to_string(parse_vertical_levels("50m", "--v")), "50m");
  for (const char* bad : {"", "1", "4097", "0m", "-5m", "m", "abc", "infm", "nanm", "5 m", "50 m",
                          "1e400m", "2x"}) {
    const std::string msg = error_of<UsageError>([&] { parse_vertical_levels(bad, "--v"); });
    EXPECT_EQ(msg, std::string("--v '") + bad +
                       "': expected finest, native, a level count N (2 to 4096) or a spacing in "
                       "metres such as 50m");
  }
}

// ---- the real WRF file -------------------------------------------------------------------

// A whole dataset of the file as doubles.
std::vector<double> read_all(const char* name, std::size_t count) {
  std::vector<double> v(count);
  hid_t f = H5Fopen(katrina_file().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  EXPECT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0) << name;
  H5Dclose(d);
  H5Fclose(f);
  return v;
}

// T (mass points, 14 levels) at the midpoints of the geopotential's 15 staggered levels, each
// step's own: its uniform grid and three columns at two steps, found here by a binary search
// over each column's heights from PH, PHB and T read whole.
TEST(LevelResample, WrfTemperatureAtItsGeopotentialHeights) {
  if (!std::filesystem::exists(katrina_file()))
    GTEST_SKIP() << "shared data absent: " << katrina_file();
  constexpr int kPlane = 48 * 48;
  const std::vector<double> ph = read_all("PH", 4 * 15 * kPlane), phb = read_all("PHB", ph.size());
  const std::vector<double> temp = read_all("T", 4 * 14 * kPlane);
  const auto stag = [&](int t, int k, int c) {
    const std::size_t i = (std::size_t(t) * 15 + std::size_t(k)) * kPlane + std::size_t(c);
    return (ph[i] + phb[i]) / 9.81;
  };
  const auto mass = [&](int t, int k, int c) { return 0.5 * (stag(t, k, c) + stag(t, k + 1, c)); };
  double bottom = std::numeric_limits<double>::infinity(), top = -bottom, finest = bottom;
  for (int c = 0; c < kPlane; ++c) {
    bottom = std::min(bottom, mass(0, 0, c));
    top = std::max(top, mass(0, 13, c));
    for (int k = 0; k < 13; ++k) finest = std::min(finest, mass(0, k + 1, c) - mass(0, k, c));
  }
  const int planes = int(std::lround((top - bottom) / finest)) + 1;
  const double dz = (top - bottom) / (planes - 1);

  auto s = tsptest::open_field(katrina_file().string(), "T");
  ASSERT_EQ(s->dims(), (Dims{48, 48, planes}));
  EXPECT_EQ(planes, 78);  // 14 levels, the thinnest ~73 m apart, over ~5.6 km
  EXPECT_NEAR(s->origin()[2], bottom, 1e-9 * bottom);
  EXPECT_NEAR(s->spacing()[2], dz, 1e-9 * dz);
  EXPECT_DOUBLE_EQ(s->spacing()[0], 10000);
  EXPECT_NE(s->describe().find("levels resampled from 14 uneven levels (geopotential) to 78 at"),
            std::string::npos)
      << s->describe();
  for (int t : {0, 3}) {
    std::vector<float> v(std::size_t(s->dims().count()));
    std::vector<std::uint8_t> inside(v.size());
    s->read_step_inside(t, v, inside);
    for (auto [x, y] : {std::pair{24, 24}, std::pair{0, 0}, std::pair{47, 30}}) {
      const int c = y * 48 + x;
      std::vector<double> h(14), val(14);
      for (int k = 0; k < 14; ++k) {
        h[std::size_t(k)] = mass(t, k, c);
        val[std::size_t(k)] = temp[(std::size_t(t) * 14 + std::size_t(k)) * kPlane + std::size_t(c)];
      }
      for (int j = 0; j < planes; ++j) {
        const double z = bottom + j * dz;
        double want;
        if (z <= h[0]) {
          want = val[0];
        } else if (z >= h[13]) {
          want = val[13];
        } else {
          const std::size_t k = std::size_t(std::upper_bound(h.begin(), h.end(), z) - h.begin()) - 1;
          want = val[k] + (val[k + 1] - val[k]) * (z - h[k]) / (h[k + 1] - h[k]);
        }
        const std::size_t i = std::size_t(j) * kPlane + std::size_t(c);
        EXPECT_NEAR(v[i], want, 1e-5 * std::fabs(want) + 1e-5) << t << " " << j << " " << x << "," << y;
        EXPECT_EQ(inside[i], z >= h[0] - dz / 2 && z <= h[13] + dz / 2 ? 1 : 0)
            << t << " " << j << " " << x << "," << y;
      }
    }
  }
}

// W on the staggered levels themselves; U, one wider in x, at the mean of the two mass
// columns beside it; both at their own step's geopotential.
TEST(LevelResample, WrfStaggeredFieldsAtTheirOwnHeights) {
  if (!std::filesystem::exists(katrina_file()))
    GTEST_SKIP() << "shared data absent: " << katrina_file();
  constexpr int kPlane = 48 * 48;
  const std::vector<double> ph = read_all("PH", 4 * 15 * kPlane), phb = read_all("PHB", ph.size());
  const auto stag = [&](int t, int k, int x, int y) {
    const std::size_t i = (std::size_t(t) * 15 + std::size_t(k)) * kPlane + std::size_t(y * 48 + x);
    return (ph[i] + phb[i]) / 9.81;
  };
  // W: plane 0 at the lowest staggered height of step 0 (the ground, 0 m over the sea).
  auto w = tsptest::open_field(katrina_file().string(), "W");
  double ground = std::numeric_limits<double>::infinity();
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x) ground = std::min(ground, stag(0, 0, x, y));
  EXPECT_EQ(w->dims().x, 48);
  EXPECT_DOUBLE_EQ(w->origin()[2], ground);
  // U at step 2, column x = 20 (between mass columns 19 and 20), y = 10: where a plane meets
  // a stored level's height exactly the value is that level's; check the interpolation between.
  auto u = tsptest::open_field(katrina_file().string(), "U");
  ASSERT_EQ(u->dims().x, 49);
  const std::vector<double> uv = read_all("U", 4 * 14 * 48 * 49);
  const int x = 20, y = 10, t = 2;
  std::vector<double> h(14), val(14);
  for (int k = 0; k < 14; ++k) {
    const double lower = 0.5 * (stag(t, k, x - 1, y) + stag(t, k, x, y));
    const double upper = 0.5 * (stag(t, k + 1, x - 1, y) + stag(t, k + 1, x, y));
    h[std::size_t(k)] = 0.5 * (lower + upper);
    val[std::size_t(k)] = uv[((std::size_t(t) * 14 + std::size_t(k)) * 48 + std::size_t(y)) * 49 + std::size_t(x)];
  }
  const std::vector<float> got = tsptest::read_step(*u, t);
  const double z0 = u->origin()[2], dz = u->spacing()[2];
  int checked = 0;
  for (int j = 0; j < u->dims().z; ++j) {
    const double z = z0 + j * dz;
    if (z <= h[0] || z >= h[13]) continue;
    const std::size_t k = std::size_t(std::upper_bound(h.begin(), h.end(), z) - h.begin()) - 1;
    const double want = val[k] + (val[k + 1] - val[k]) * (z - h[k]) / (h[k + 1] - h[k]);
    EXPECT_NEAR(got[(std::size_t(j) * 48 + std::size_t(y)) * 49 + std::size_t(x)], want,
                1e-5 * std::fabs(want) + 1e-5)
        << j;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

// --vertical-levels native: the levels as stored (14), at their mean spacing.
TEST(LevelResample, WrfNativeKeepsTheStoredLevels) {
  if (!std::filesystem::exists(katrina_file()))
    GTEST_SKIP() << "shared data absent: " << katrina_file();
  SourceOptions o;
  o.field = "T";
  o.vertical.mode = VerticalLevels::Mode::native;
  auto s = open_source(katrina_file().string(), o);
  EXPECT_EQ(s->dims(), (Dims{48, 48, 14}));
  EXPECT_FALSE(s->has_stencil());
  EXPECT_EQ(s->describe().find("resampled"), std::string::npos);
}

}  // namespace
}  // namespace tsp

#include "tsp/source/open_source.h"
#include "tsp/source/raw_source.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;
using tsptest::error_of;
using tsptest::expect_formula;
using tsptest::kFixtureDims;

// Writes f at time t as raw samples of type T, little or big endian, x fastest.
template <typename T>
void write_raw(const fs::path& p, double t, bool big_endian, Dims d = kFixtureDims) {
  std::ofstream out(p, std::ios::binary);
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        T v = static_cast<T>(tsptest::formula(x, y, z, t));
        unsigned char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        if (big_endian != (std::endian::native == std::endian::big))
          for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(b[k], b[sizeof(T) - 1 - k]);
        out.write(reinterpret_cast<const char*>(b), sizeof(T));
      }
}

SourceOptions raw_options(RawType type = RawType::f32, bool big_endian = false) {
  SourceOptions o;
  o.raw_dims = kFixtureDims;
  o.raw_type = type;
  o.raw_big_endian = big_endian;
  return o;
}

TEST(RawSource, PrintfPatternFromZeroUntilFirstGap) {
  fs::path dir = tsptest::temp_dir();
  for (int t : {0, 1, 2, 4}) {  // 3 is missing: the series stops at 2
    char name[32];
    std::snprintf(name, sizeof name, "u_%04d.raw", t);
    write_raw<float>(dir / name, t, false);
  }
  auto s = open_source((dir / "u_%04d.raw").string(), raw_options());
  EXPECT_EQ(s->dims(), kFixtureDims);
  ASSERT_EQ(s->steps(), 3);
  for (int t = 0; t < 3; ++t) expect_formula(tsptest::read_step(*s, t), kFixtureDims, t);
}

TEST(RawSource, PrintfPatternStartsAtOneWhenZeroIsMissing) {
  fs::path dir = tsptest::temp_dir();
  for (int t : {1, 2}) write_raw<float>(dir / ("v" + std::to_string(t) + ".raw"), t, false);
  auto s = open_source((dir / "v%d.raw").string(), raw_options());
  ASSERT_EQ(s->steps(), 2);
  expect_formula(tsptest::read_step(*s, 0), kFixtureDims, 1);
  expect_formula(tsptest::read_step(*s, 1), kFixtureDims, 2);
}

TEST(RawSource, GlobSortsNumericAware) {
  fs::path dir = tsptest::temp_dir();
  for (int t : {10, 2, 1}) write_raw<float>(dir / ("s" + std::to_string(t) + ".raw"), t, false);
  auto s = open_source((dir / "s*.raw").string(), raw_options());
  ASSERT_EQ(s->steps(), 3);
  const int order[] = {1, 2, 10};
  for (int i = 0; i < 3; ++i) expect_formula(tsptest::read_step(*s, i), kFixtureDims, order[i]);
}

TEST(RawSource, EveryTypeAndByteOrder) {
  fs::path dir = tsptest::temp_dir();
  // Values up to 2234 + 1000·t: u8 would wrap, so the u8 case uses a 2 × 2 × 2 grid, t = 0.
  {
    Dims small{2, 2, 2};
    write_raw<std::uint8_t>(dir / "b_0.raw", 0, false, small);
    SourceOptions o = raw_options(RawType::u8);
    o.raw_dims = small;
    auto s = open_source((dir / "b_%d.raw").string(), o);
    expect_formula(tsptest::read_step(*s, 0), small, 0);
  }
  for (bool big : {false, true}) {
    std::string tag = big ? "be" : "le";
    write_raw<std::uint16_t>(dir / ("w" + tag + "_0.raw"), 1, big);
    auto s16 =
        open_source((dir / ("w" + tag + "_%d.raw")).string(), raw_options(RawType::u16, big));
    expect_formula(tsptest::read_step(*s16, 0), kFixtureDims, 1);
    write_raw<float>(dir / ("f" + tag + "_0.raw"), 2, big);
    auto s32 =
        open_source((dir / ("f" + tag + "_%d.raw")).string(), raw_options(RawType::f32, big));
    expect_formula(tsptest::read_step(*s32, 0), kFixtureDims, 2);
  }
}

TEST(RawSource, WrongFileSizeNamesFileAndBytes) {
  fs::path dir = tsptest::temp_dir();
  write_raw<float>(dir / "a_0.raw", 0, false);
  write_raw<float>(dir / "a_1.raw", 1, false, Dims{5, 4, 2});
  std::string msg =
      error_of<FormatError>([&] { open_source((dir / "a_%d.raw").string(), raw_options()); });
  EXPECT_NE(msg.find("a_1.raw"), std::string::npos) << msg;
  EXPECT_NE(msg.find("holds 160 bytes, expected 240"), std::string::npos) << msg;
}

TEST(RawSource, FileShrunkAfterOpenFailsAtRead) {
  fs::path dir = tsptest::temp_dir();
  write_raw<float>(dir / "c_0.raw", 0, false);
  auto s = open_source((dir / "c_%d.raw").string(), raw_options());
  fs::resize_file(dir / "c_0.raw", 100);
  std::string msg = error_of<FormatError>([&] { tsptest::read_step(*s, 0); });
  EXPECT_NE(msg.find("c_0.raw"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected 240"), std::string::npos) << msg;
}

TEST(RawSource, NoMatchIsAnIoErrorNamingThePattern) {
  fs::path dir = tsptest::temp_dir();
  std::string pattern = (dir / "none_%03d.raw").string();
  std::string msg = error_of<IoError>([&] { open_source(pattern, raw_options()); });
  EXPECT_NE(msg.find(pattern), std::string::npos) << msg;
  std::string glob = (dir / "none_*.raw").string();
  msg = error_of<IoError>([&] { open_source(glob, raw_options()); });
  EXPECT_NE(msg.find(glob), std::string::npos) << msg;
}

TEST(RawSource, MissingOrBadDimsIsAUsageError) {
  fs::path dir = tsptest::temp_dir();
  write_raw<float>(dir / "d_0.raw", 0, false);
  SourceOptions o;
  std::string msg = error_of<UsageError>([&] { open_source((dir / "d_%d.raw").string(), o); });
  EXPECT_NE(msg.find("--raw-dims"), std::string::npos) << msg;
  o.raw_dims = Dims{5, 0, 3};
  EXPECT_THROW(open_source((dir / "d_%d.raw").string(), o), UsageError);
}

TEST(RawSource, MalformedPrintfPatternIsAUsageError) {
  fs::path dir = tsptest::temp_dir();
  EXPECT_THROW(open_source((dir / "x_%s.raw").string(), raw_options()), UsageError);
  EXPECT_THROW(open_source((dir / "x_%d_%d.raw").string(), raw_options()), UsageError);
}

TEST(RawSource, PercentEscapeInPattern) {
  fs::path dir = tsptest::temp_dir();
  write_raw<float>(dir / "p%_0.raw", 0, false);
  write_raw<float>(dir / "p%_1.raw", 1, false);
  auto s = open_source((dir / "p%%_%d.raw").string(), raw_options());
  ASSERT_EQ(s->steps(), 2);
  expect_formula(tsptest::read_step(*s, 1), kFixtureDims, 1);
}

TEST(RawSource, SingleRawFileIsOneStep) {
  fs::path dir = tsptest::temp_dir();
  write_raw<float>(dir / "one.raw", 2, false);
  auto s = open_source((dir / "one.raw").string(), raw_options());
  ASSERT_EQ(s->steps(), 1);
  expect_formula(tsptest::read_step(*s, 0), kFixtureDims, 2);
}

}  // namespace
}  // namespace tsp

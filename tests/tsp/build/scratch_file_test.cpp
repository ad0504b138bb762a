// The builder's scratch file: brick-major series written step by step and read back whole,
// from several threads, nothing left in the directory, and unwritable directories refused.
#include "tsp/build/scratch_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <thread>
#include <vector>

#include "support/paths.h"
#include "tsp/core/error.h"

namespace {

namespace fs = std::filesystem;

float value(int brick, int step, int i) { return float(brick * 1000 + step * 100 + i) + 0.25f; }

TEST(ScratchFile, SeriesComeBackBrickMajorAndNothingIsLeftBehind) {
  const auto dir = tsptest::temp_dir();
  const std::vector<std::int64_t> samples = {5, 1, 12};
  const int steps = 4;
  {
    tsp::ScratchFile f(dir.string(), samples, steps);
    EXPECT_EQ(f.size_bytes(), (5 + 1 + 12) * steps * std::int64_t(sizeof(float)));
    EXPECT_TRUE(fs::is_empty(dir));  // unlinked at once
    // Steps written in any order, bricks from two threads.
    std::thread other([&] {
      for (int t = steps - 1; t >= 0; --t) {
        std::vector<float> v(12);
        for (int i = 0; i < 12; ++i) v[std::size_t(i)] = value(2, t, i);
        f.write(2, t, v);
      }
    });
    for (int t = 0; t < steps; ++t)
      for (int b : {0, 1}) {
        std::vector<float> v(std::size_t(samples[std::size_t(b)]));
        for (std::size_t i = 0; i < v.size(); ++i) v[i] = value(b, t, int(i));
        f.write(b, t, v);
      }
    other.join();
    for (int b = 0; b < 3; ++b) {
      const auto n = std::size_t(samples[std::size_t(b)]);
      std::vector<float> series(n * steps);
      f.read_series(b, series);
      for (int t = 0; t < steps; ++t)
        for (std::size_t i = 0; i < n; ++i)
          ASSERT_EQ(series[std::size_t(t) * n + i], value(b, t, int(i)))
              << "brick " << b << " step " << t << " sample " << i;
      f.discard(b);
    }
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(ScratchFile, UnwritableDirectoryIsAnIoErrorNamingIt) {
  const auto dir = tsptest::temp_dir() / "missing";
  try {
    tsp::ScratchFile f(dir.string(), {8}, 2);
    FAIL() << "no error";
  } catch (const tsp::IoError& e) {
    EXPECT_NE(std::string(e.what()).find(dir.string()), std::string::npos) << e.what();
  }
}

}  // namespace

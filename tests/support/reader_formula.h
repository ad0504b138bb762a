// The analytic field every reader fixture in tests/data holds (see tests/data/make_fixtures.py).
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "support/paths.h"
#include "tsp/core/types.h"
#include "tsp/source/open_source.h"
#include "tsp/source/volume_source.h"

namespace tsptest {

/// f(x, y, z, t) = x + 10·y + 100·z + 1000·t, exact in float for the fixtures' small grids.
inline float formula(int x, int y, int z, double t) {
  return float(x + 10 * y + 100 * z + 1000 * t);
}

/// Fixture grid: 5 × 4 × 3 points; cell fields live on 4 × 3 × 2 cells.
inline constexpr tsp::Dims kFixtureDims{5, 4, 3};
inline constexpr tsp::Dims kFixtureCellDims{4, 3, 2};

/// Expects out (x fastest) to equal formula(x, y, z, t) + add everywhere.
inline void expect_formula(std::span<const float> out, tsp::Dims d, double t, float add = 0) {
  ASSERT_EQ(std::int64_t(out.size()), d.count());
  int bad = 0;
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        float want = formula(x, y, z, t) + add;
        float got = out[std::size_t((z * d.y + y) * d.x + x)];
        if (got != want && bad++ < 5)
          ADD_FAILURE() << "at (" << x << "," << y << "," << z << ") t=" << t << ": got " << got
                        << ", want " << want;
      }
  EXPECT_EQ(bad, 0);
}

/// Opens path through open_source with only the field set.
inline std::unique_ptr<tsp::VolumeSource> open_field(const std::filesystem::path& path,
                                                     const std::string& field) {
  tsp::SourceOptions o;
  o.field = field;
  return tsp::open_source(path.string(), o);
}

/// Path of the HDF5 reader fixture `name` (tests/data/h5).
inline std::string h5_fixture(const std::string& name) {
  return (test_data_dir() / "h5" / name).string();
}

/// Reads step t of s into a new vector.
inline std::vector<float> read_step(tsp::VolumeSource& s, int t) {
  std::vector<float> out(std::size_t(s.dims().count()));
  s.read_step(t, out);
  return out;
}

/// Expects s to hold grid d and one step per entry of ts, step i equal to formula at t = ts[i].
inline void expect_steps(tsp::VolumeSource& s, tsp::Dims d, const std::vector<double>& ts) {
  EXPECT_EQ(s.dims(), d);
  ASSERT_EQ(s.steps(), int(ts.size()));
  for (int t = 0; t < s.steps(); ++t) expect_formula(read_step(s, t), d, ts[std::size_t(t)]);
}

/// Message of the E the callable throws; fails the test when it throws nothing or another type.
template <typename E, typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return "";
  }
  ADD_FAILURE() << "no exception";
  return "";
}

}  // namespace tsptest

// tspplay generate: runs the built CLI and checks its files and exit codes.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <vector>

#include "support/paths.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/source/procedural/generate.h"

namespace {

namespace fs = std::filesystem;
using tsptest::run_tspplay;

using tsptest::q;

TEST(GenerateCli, ListNamesEveryDataset) {
  auto r = run_tspplay("generate --list");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const auto& d : tsp::list_datasets()) {
    EXPECT_NE(r.out.find(d.name), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(d.description), std::string::npos) << r.out;
  }
}

TEST(GenerateCli, WritesTheNamedDatasetWithOptions) {
  const fs::path out = tsptest::temp_dir() / "v.h5";
  auto r = run_tspplay("generate vortex -o " + q(out) + " --dims 8,9,10 --steps 3 --seed 7");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  tsp::h5::Handle f = tsp::h5::open_file_readonly(out.string());
  tsp::h5::Handle d(H5Dopen2(f.get(), "/vortex", H5P_DEFAULT));
  ASSERT_TRUE(d);
  EXPECT_EQ(tsp::h5::dataset_shape(d.get()), (std::vector<hsize_t>{3, 10, 9, 8}));
  tsp::h5::Handle a(H5Aopen(d.get(), "seed", H5P_DEFAULT));
  std::uint64_t seed = 0;
  ASSERT_GE(H5Aread(a.get(), H5T_NATIVE_UINT64, &seed), 0);
  EXPECT_EQ(seed, 7u);
  tsp::h5::Handle ver(H5Aopen(d.get(), "generator_version", H5P_DEFAULT));
  std::int64_t version = 0;
  ASSERT_GE(H5Aread(ver.get(), H5T_NATIVE_INT64, &version), 0);
  EXPECT_EQ(version, tsp::kGeneratorVersion);

  std::vector<float> file(3 * 10 * 9 * 8), step(10 * 9 * 8);
  ASSERT_GE(H5Dread(d.get(), H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, file.data()), 0);
  tsp::GenerateOptions o;
  o.dims = tsp::Dims{8, 9, 10};
  o.steps = 3;
  o.seed = 7;
  auto src = tsp::make_generated_source("vortex", o);
  for (int t = 0; t < 3; ++t) {
    src->read_step(t, step);
    for (std::size_t i = 0; i < step.size(); ++i)
      ASSERT_EQ(file[t * step.size() + i], step[i]) << t << " " << i;
  }
}

TEST(GenerateCli, DefaultsToShockAt64Cubed) {
  const fs::path out = tsptest::temp_dir() / "s.h5";
  auto r = run_tspplay("generate -o " + q(out) + " --steps 2 --dims 64");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  tsp::h5::Handle f = tsp::h5::open_file_readonly(out.string());
  tsp::h5::Handle d(H5Dopen2(f.get(), "/shock", H5P_DEFAULT));
  ASSERT_TRUE(d);
  EXPECT_EQ(tsp::h5::dataset_shape(d.get()), (std::vector<hsize_t>{2, 64, 64, 64}));
}

TEST(GenerateCli, BadArgumentsAreUsageErrorsNamingWhatWasExpected) {
  const fs::path dir = tsptest::temp_dir();
  const std::string o = " -o " + q(dir / "x.h5");
  struct Case {
    std::string args, expect;
  } cases[] = {
      {"generate nope" + o, "shock, vortex"},
      {"generate shock" + o + " --dims 0,4,4", "X,Y,Z"},
      {"generate shock" + o + " --dims 4,4", "X,Y,Z"},
      {"generate shock" + o + " --dims 4,4,4,4", "X,Y,Z"},
      {"generate shock" + o + " --dims abc", "X,Y,Z"},
      {"generate shock" + o + " --dims 4,4,99999", "2048"},
      {"generate shock" + o + " --steps 0", "step count"},
      {"generate shock" + o + " --steps 2x", "step count"},
      {"generate shock" + o + " --seed -1", "non-negative"},
      {"generate shock" + o + " --gzip 12", "0..9"},
      {"generate shock", "-o"},
  };
  for (const auto& c : cases) {
    auto r = run_tspplay(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << "\n" << r.err;
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(GenerateCli, UnwritableOutputIsAnErrorAndWritesNothing) {
  const fs::path dir = tsptest::temp_dir();
  auto r = run_tspplay("generate shock -o " + q(dir / "missing" / "x.h5") + " --dims 4 --steps 1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("missing"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace

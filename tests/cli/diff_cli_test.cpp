#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "support/paths.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"

namespace {

namespace fs = std::filesystem;
using tsptest::run_tspplay;

tsp::Image random_image(int w, int h, unsigned seed) {
  tsp::Image img(w, h);
  std::mt19937 rng(seed);
  for (auto& v : img.rgba) v = std::uint8_t(rng());
  return img;
}

using tsptest::q;

struct Pair {
  fs::path dir, a, b;
  tsp::Image ia, ib;
};

Pair make_pair_files(int w, int h) {
  Pair p;
  p.dir = tsptest::temp_dir();
  p.a = p.dir / "a.png";
  p.b = p.dir / "b.png";
  p.ia = random_image(w, h, 1);
  p.ib = random_image(w, h, 2);
  tsp::write_png(p.a.string(), p.ia);
  tsp::write_png(p.b.string(), p.ib);
  return p;
}

TEST(DiffCli, JsonMatchesTheLibraryAndWritesTheDifferenceImage) {
  const Pair p = make_pair_files(21, 13);
  const fs::path out = p.dir / "d.png";
  const auto r = run_tspplay("diff " + q(p.a) + " " + q(p.b) + " --json -o " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  tsp::Image want_img;
  const tsp::DiffStats want = tsp::diff_images(p.ia, p.ib, &want_img);
  EXPECT_DOUBLE_EQ(j.at("mean").get<double>(), want.mean);
  EXPECT_DOUBLE_EQ(j.at("p99").get<double>(), want.p99);
  EXPECT_DOUBLE_EQ(j.at("max").get<double>(), want.max);
  EXPECT_EQ(j.at("pixels").get<int>(), 21 * 13);
  EXPECT_EQ(j.at("width").get<int>(), 21);
  EXPECT_EQ(j.at("height").get<int>(), 13);
  EXPECT_GT(want.mean, 1.0);  // random images really differ
  EXPECT_EQ(tsp::read_png(out.string()).rgba, want_img.rgba);
}

TEST(DiffCli, TextOutputOfIdenticalImagesIsZero) {
  const Pair p = make_pair_files(5, 4);
  const auto r = run_tspplay("diff " + q(p.a) + " " + q(p.a));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("5x4 pixels"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mean 0.0000  p99 0.0000  max 0.0000"), std::string::npos) << r.out;
}

TEST(DiffCli, SizeMismatchIsAUsageErrorNamingBothFiles) {
  const Pair p = make_pair_files(5, 4);
  const fs::path c = p.dir / "c.png";
  tsp::write_png(c.string(), tsp::Image(4, 5));
  const auto r = run_tspplay("diff " + q(p.a) + " " + q(c));
  EXPECT_EQ(r.exit_code, 2);
  for (const std::string& part : {p.a.string(), c.string(), std::string("5x4"), std::string("4x5")})
    EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
}

TEST(DiffCli, MissingAndNonPngInputsFailNamingTheFileAndWriteNothing) {
  const Pair p = make_pair_files(3, 3);
  const fs::path missing = p.dir / "missing.png", text = p.dir / "text.png",
                 out = p.dir / "out.png";
  std::ofstream(text) << "not a png\n";
  for (const fs::path& bad : {missing, text}) {
    const auto r = run_tspplay("diff " + q(p.a) + " " + q(bad) + " -o " + q(out));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST(DiffCli, MissingArgumentIsAUsageError) {
  EXPECT_EQ(run_tspplay("diff only_one.png").exit_code, 2);
}

}  // namespace

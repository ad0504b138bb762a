// tspplay demo end to end: the files it promises, the report's contents checked against the
// .tsp file it built, reuse on a second run, and usage errors that leave nothing behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/json_file.h"
#include "support/paths.h"
#include "tsp/source/open_source.h"
#include "tsp/source/procedural/generate.h"
#include "tsp/source/volume_source.h"
#include "tsp/store/tsp_file.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tsptest::run_tspplay;

TEST(DemoCli, GeneratesBuildsReportsAndReuses) {
  fs::path dir = tsptest::temp_dir() / "demo";
  auto r = run_tspplay("demo -o '" + dir.string() + "' --dims 20,17,9 --steps 5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path h5 = dir / "shock_20x17x9_5.h5", tsp_path = dir / "shock_20x17x9_5.tsp";
  ASSERT_TRUE(fs::exists(h5));
  ASSERT_TRUE(fs::exists(tsp_path));
  ASSERT_TRUE(fs::exists(dir / "auto_tf.json"));

  // The .h5 holds exactly what the generator makes.
  auto gen = tsp::make_generated_source("shock", {tsp::Dims{20, 17, 9}, 5});
  tsp::SourceOptions so;
  so.field = "shock";
  auto back = tsp::open_source(h5.string(), so);
  std::vector<float> a(gen->dims().count()), b(a.size());
  for (int t = 0; t < 5; ++t) {
    gen->read_step(t, a);
    back->read_step(t, b);
    ASSERT_EQ(a, b) << "step " << t;
  }

  json rep = tsptest::read_json(dir / "report.json");
  auto file = tsp::TspFile::open(tsp_path.string());
  EXPECT_EQ(rep["dataset"]["name"], "shock");
  EXPECT_EQ(rep["tree"]["tsp_nodes"], file->tree().size());
  EXPECT_EQ(rep["tree"]["steps"], 5);
  ASSERT_EQ(rep["metrics"].size(), 4u);
  for (const auto& m : rep["metrics"]) {
    EXPECT_EQ(m["tsp_nodes"], file->tree().size());
    // The same count `tspplay metrics --json` gives for the demo's TF file.
    const std::string name = m["metric"].get<std::string>();
    auto mr = run_tspplay("metrics " + tsptest::quote(tsp_path) + " --tf " +
                          tsptest::quote(dir / "auto_tf.json") + " --metric " + name + " --json");
    ASSERT_EQ(mr.exit_code, 0) << mr.err;
    const json mj = json::parse(mr.out);
    EXPECT_EQ(m["transparent_nodes"], mj["transparent_nodes"]) << name;
    // (The default map, preset:auto, leaves no node of this small shock wholly clear: every
    // node holds some value off the background's; on the 64³ demo it hides 2646 of 10773.)
  }
  // Every metric uses the same exact transparency test, so they agree on the count.
  EXPECT_EQ(rep["metrics"][0]["transparent_nodes"], rep["metrics"][3]["transparent_nodes"]);
  EXPECT_GT(rep["build"]["source_bytes"].get<long long>(), 0);

  auto again = run_tspplay("demo -o '" + dir.string() + "' --dims 20,17,9 --steps 5");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("reusing " + h5.string()), std::string::npos) << again.out;
  EXPECT_NE(again.out.find("reusing " + tsp_path.string()), std::string::npos) << again.out;
}

TEST(DemoCli, BadOptionsAreUsageErrorsAndWriteNothing) {
  fs::path dir = tsptest::temp_dir() / "demo";
  for (const char* args : {"--steps 0", "--dims 4,4", "--dataset nope"}) {
    auto r = run_tspplay("demo -o '" + dir.string() + "' " + args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("usage error"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir)) << args;
  }
}

}  // namespace

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "support/paths.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/store/tsp_file.h"

namespace {

using nlohmann::json;
using tsptest::run_tspplay;

// A small .tsp built through the CLI from a generated dataset (once per test
// binary).
const std::string &small_tsp() {
  static const std::string path = [] {
    const auto dir = tsptest::temp_dir();
    const std::string h5 = (dir / "shock.h5").string(),
                      tsp = (dir / "shock.tsp").string();
    auto g = run_tspplay("generate shock -o '" + h5 + "' --dims 24 --steps 4");
    EXPECT_EQ(g.exit_code, 0) << g.err;
    auto b = run_tspplay("build '" + h5 + "' -o '" + tsp + "' --brick 8");
    EXPECT_EQ(b.exit_code, 0) << b.err;
    return tsp;
  }();
  return path;
}

json run_json(const std::string &args) {
  auto r = run_tspplay(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return json::parse(r.out);
}

TEST(MetricsCli, JsonNodesMatchTheLibraryForEveryMetric) {
  const std::string tsp = small_tsp();
  auto file = tsp::TspFile::open(tsp);
  const tsp::TransferFunction tf =
      tsp::preset_transfer_function("sparse", file->tree().value_range());
  for (const char *m : {"scalar", "reference", "approximate", "perceptual"}) {
    json j = run_json("metrics '" + tsp + "' --tf preset:sparse --metric " + m +
                      " --json --nodes");
    const tsp::MetricResult want = tsp::compute_errors(
        tsp::parse_metric(m), file->tree(), tf, file.get(), 1);
    EXPECT_EQ(j["metric"], m);
    EXPECT_GE(j["recompute_ms"].get<double>(), 0.0);
    EXPECT_EQ(j["tsp_nodes"], file->tree().size());
    EXPECT_EQ(j["transparent_nodes"], want.transparent_count());
    ASSERT_EQ(j["nodes"].size(), std::size_t(file->tree().size()));
    for (const json &n : j["nodes"]) {
      const int id = n["id"];
      EXPECT_FLOAT_EQ(n["spatial_error"].get<float>(), want.errors.spatial[id])
          << m << " " << id;
      EXPECT_FLOAT_EQ(n["temporal_error"].get<float>(),
                      want.errors.temporal[id])
          << m << " " << id;
      EXPECT_EQ(n["transparent"].get<bool>(), bool(want.transparent[id]));
      ASSERT_EQ(n["mean_colour"].size(), 4u);
      EXPECT_FLOAT_EQ(n["mean_colour"][3].get<float>(), want.mean_colour[id].a);
    }
  }
}

TEST(MetricsCli, IdsAreThoseOfInfoNodes) {
  const std::string tsp = small_tsp();
  json info = run_json("info '" + tsp + "' --json --nodes");
  json met = run_json("metrics '" + tsp +
                      "' --tf preset:filled --metric scalar --json --nodes");
  ASSERT_EQ(info["nodes"].size(), met["nodes"].size());
  for (std::size_t i = 0; i < met["nodes"].size(); ++i) {
    EXPECT_EQ(info["nodes"][i]["id"], met["nodes"][i]["id"]);
    // The scalar metric's errors are the stored statistics that info prints.
    EXPECT_FLOAT_EQ(info["nodes"][i]["spatial_error"].get<float>(),
                    met["nodes"][i]["spatial_error"].get<float>());
  }
  EXPECT_EQ(met["transparent_nodes"], 0); // "filled" shows every value
}

TEST(MetricsCli, TextOutputAndTfFile) {
  const std::string tsp = small_tsp();
  const auto tfpath = tsptest::temp_dir() / "tf.json";
  std::ofstream(tfpath)
      << R"({"range": [0, 1], "points": [[0, 0, 0, 1, 0.2], [1, 1, 0, 0, 0.8]]})";
  auto r = run_tspplay("metrics '" + tsp + "' --tf '" + tfpath.string() +
                       "' --metric perceptual");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("perceptual"), std::string::npos);
  EXPECT_NE(r.out.find("recompute"), std::string::npos);
  EXPECT_NE(r.out.find("transparent"), std::string::npos);
  EXPECT_NE(r.out.find("spatial"), std::string::npos);
}

TEST(MetricsCli, BadInputsGiveClearErrors) {
  const std::string tsp = small_tsp();
  const auto bad = tsptest::temp_dir() / "bad.json";
  std::ofstream(bad) << R"({"range": [0, 1], "points": [[0, 0, 0, 0]]})";
  auto r = run_tspplay("metrics '" + tsp + "' --tf '" + bad.string() + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("points[0]"), std::string::npos) << r.err;
  r = run_tspplay("metrics '" + tsp + "' --tf preset:filled --metric nope");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = run_tspplay("metrics '" + tsp + "' --tf preset:nope");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = run_tspplay("metrics /nonexistent.tsp --tf preset:filled");
  EXPECT_EQ(r.exit_code, 1) << r.err;
}

} // namespace

// tsp::parse_json: the one JSON reader refuses nesting deeper than its limit (a 100,000-deep
// file crashed every reader) and quotes at most a short excerpt in its errors; the TF and file
// series readers go through it.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "support/paths.h"
#include "tsp/core/error.h"
#include "tsp/core/json_read.h"
#include "tsp/metric/tf_io.h"
#include "tsp/source/series_list.h"

namespace {

std::string nested(int depth) { return std::string(std::size_t(depth), '[') + std::string(std::size_t(depth), ']'); }

std::string error_of(const std::string& text) {
  try {
    tsp::parse_json(text, "doc.json");
  } catch (const tsp::FormatError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted";
  return "";
}

TEST(JsonRead, ParsesUpToTheDepthLimitAndRefusesDeeper) {
  EXPECT_EQ(tsp::parse_json(nested(tsp::kMaxJsonDepth), "ok.json").size(), 1u);
  EXPECT_EQ(tsp::parse_json(R"({"a": [1, 2, {"b": 3}]})", "ok.json")["a"][2]["b"], 3);
  const std::string deep = error_of(nested(tsp::kMaxJsonDepth + 1));
  EXPECT_NE(deep.find("doc.json: not valid JSON: arrays and objects nested deeper than 64"),
            std::string::npos)
      << deep;
  // 100,000 deep: an error, not a crash, and the message stays short.
  EXPECT_LT(error_of(nested(100000)).size(), 200u);
  EXPECT_LT(error_of(std::string(50000, '[') + "x").size(), 300u);
  EXPECT_NE(error_of("{\"a\": 1e999}").find("doc.json: not valid JSON"), std::string::npos);
}

TEST(JsonRead, TransferFunctionAndSeriesReadersUseTheLimit) {
  const std::string deep = "{\"range\": " + nested(100000) + "}";
  try {
    tsp::parse_transfer_function(deep, "tf.json", 256);
    ADD_FAILURE() << "a 100,000-deep TF was accepted";
  } catch (const tsp::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("tf.json: not valid JSON"), std::string::npos);
    EXPECT_LT(std::string(e.what()).size(), 200u);
  }
  const auto path = tsptest::temp_dir() / "deep.vtu.series";
  std::ofstream(path) << "{\"file-series-version\": \"1.0\", \"files\": " << nested(100000) << "}";
  EXPECT_THROW(tsp::io::read_file_series(path.string()), tsp::FormatError);
}

}  // namespace

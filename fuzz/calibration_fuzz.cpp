// Fuzz target: the --quality calibration cache (JSON): parsed, validated and queried. A corrupt
// cache is recomputed, so bad input must end in a tsp::Error exception, never a crash.
#include <nlohmann/json.hpp>
#include <string>

#include "fuzz_input.h"
#include "jobs/calibration.h"
#include "tsp/core/json_read.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // The cache reader's own path (calibration.cpp): tsp::parse_json (nesting limit, messages
  // cut), then the checks; anything it refuses is a tsp::Error and the cache is recomputed.
  tspfuzz::expect_clean([&] {
    const tspgl::Calibration c = tspgl::calibration_from_json(tsp::parse_json(text, "fuzz.json"), "fuzz.json");
    for (double de : {0.5, 1.0, 3.0, 50.0}) (void)tspgl::pick_configuration(c, de);
    (void)tspgl::to_json(c);
  });
  return 0;
}

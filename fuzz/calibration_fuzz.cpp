// Fuzz target: the --quality calibration cache (JSON): parsed, validated and queried. A corrupt
// cache is recomputed, so bad input must end in a json or tsp::Error exception, never a crash.
#include <nlohmann/json.hpp>
#include <string>

#include "fuzz_input.h"
#include "jobs/calibration.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    return 0;  // not JSON: the cache reader recomputes
  }
  tspfuzz::expect_clean([&] {
    const tspgl::Calibration c = tspgl::calibration_from_json(j, "fuzz.json");
    for (double de : {0.5, 1.0, 3.0, 50.0}) (void)tspgl::pick_configuration(c, de);
    (void)tspgl::to_json(c);
  });
  return 0;
}

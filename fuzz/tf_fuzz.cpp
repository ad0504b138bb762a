// Fuzz target: transfer-function JSON (our format and ParaView presets), parsed and sampled.
#include <string>

#include "fuzz_input.h"
#include "tsp/metric/tf_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  tspfuzz::expect_clean([&] {
    tsp::TransferFunction tf = tsp::parse_transfer_function(text, "fuzz.json", 64);
    for (int j = 0; j < tf.size(); ++j) (void)tf.entry(j);
  });
  return 0;
}

// Fuzz target: one .vti file (VTK XML image data: ascii, base64, appended raw/base64, zlib) read
// through open_source and every step decoded.
#include <vector>

#include "fuzz_input.h"
#include "tsp/source/open_source.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = tspfuzz::write_input("input.vti", data, size);
  tspfuzz::expect_clean([&] {
    auto s = tsp::open_source(path, {});
    std::vector<float> v(std::size_t(s->dims().count()));
    for (int t = 0; t < s->steps(); ++t) s->read_step(t, v);
  });
  return 0;
}

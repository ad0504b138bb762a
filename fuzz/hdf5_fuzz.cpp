// Fuzz target: an HDF5 file (plain datasets, groups of steps, NetCDF-4, VTKHDF image data) read
// through open_source, every step decoded.
#include <vector>

#include "fuzz_input.h"
#include "tsp/source/open_source.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = tspfuzz::write_input("input.h5", data, size);
  tspfuzz::expect_clean([&] {
    auto s = tsp::open_source(path, {});
    std::vector<float> v(std::size_t(s->dims().count()));
    for (int t = 0; t < s->steps() && t < 16; ++t) s->read_step(t, v);
  });
  return 0;
}

// Fuzz target: raw-series file patterns (printf %d patterns and globs) and their files: the
// first line is the pattern (relative to the scratch directory), the rest the bytes of every
// file it may match; the grid is 2 × 2 × 2 float32.
#include <string>
#include <vector>

#include "fuzz_input.h"
#include "tsp/source/open_source.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string all(reinterpret_cast<const char*>(data), size);
  const std::size_t nl = all.find('\n');
  if (nl == std::string::npos || nl == 0 || nl > 64) return 0;
  const std::string pattern = all.substr(0, nl);
  if (pattern.find('/') != std::string::npos || pattern.find("..") != std::string::npos) return 0;
  const std::string body = all.substr(nl + 1);
  for (const char* name : {"r_0.raw", "r_1.raw", "r_01.raw", "r_2.raw"})
    tspfuzz::write_input(name, reinterpret_cast<const std::uint8_t*>(body.data()), body.size());
  tspfuzz::expect_clean([&] {
    tsp::SourceOptions o;
    o.raw_dims = tsp::Dims{2, 2, 2};
    auto s = tsp::open_source((tspfuzz::scratch_dir() / pattern).string(), o);
    std::vector<float> v(std::size_t(s->dims().count()));
    for (int t = 0; t < s->steps() && t < 8; ++t) s->read_step(t, v);
  });
  return 0;
}

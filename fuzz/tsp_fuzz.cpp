// Fuzz target: a .tsp file opened and every stored brick (leaves and LOD levels) of the first and
// last step read.
#include <vector>

#include "fuzz_input.h"
#include "tsp/store/tsp_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = tspfuzz::write_input("input.tsp", data, size);
  tspfuzz::expect_clean([&] {
    auto f = tsp::TspFile::open(path);
    const tsp::Octree& o = f->tree().octree();
    std::vector<std::uint16_t> codes;
    for (int t : {0, f->tree().time().steps() - 1})
      for (int b = 0; b < o.stored_brick_count(); ++b) {
        codes.resize(std::size_t(o.lattice(b).count()));
        f->read_brick(b, t, codes);
      }
  });
  return 0;
}

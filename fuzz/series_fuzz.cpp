// Fuzz target: a .pvd (XML) or .vti.series (JSON) list of steps, resolved against the scratch
// directory (which holds one valid .vti step, step.vti): the first byte picks the form.
#include <vector>

#include "fuzz_input.h"
#include "tsp/source/open_source.h"

namespace {
const char kStep[] =
    "<?xml version=\"1.0\"?><VTKFile type=\"ImageData\" version=\"0.1\"><ImageData "
    "WholeExtent=\"0 1 0 1 0 0\"><Piece Extent=\"0 1 0 1 0 0\"><PointData Scalars=\"f\">"
    "<DataArray type=\"Float32\" Name=\"f\" format=\"ascii\">1 2 3 4</DataArray></PointData>"
    "</Piece></ImageData></VTKFile>";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  tspfuzz::write_input("step.vti", reinterpret_cast<const std::uint8_t*>(kStep), sizeof kStep - 1);
  const bool pvd = data[0] & 1;
  const std::string path =
      tspfuzz::write_input(pvd ? "input.pvd" : "input.vti.series", data + 1, size - 1);
  tspfuzz::expect_clean([&] {
    auto s = tsp::open_source(path, {});
    std::vector<float> v(std::size_t(s->dims().count()));
    for (int t = 0; t < s->steps(); ++t) s->read_step(t, v);
  });
  return 0;
}

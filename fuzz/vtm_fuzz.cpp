// Fuzz target: the indirection of unstructured inputs — a .vtm multiblock file, or a
// .vtm.series / .vtu.series (JSON) or .pvd (XML) list — resolved against the scratch directory,
// which holds one valid tetrahedron (block.vtu), a .vtm naming it (step.vtm) and a FIFO
// (fifo.vtu): a list or block that names the FIFO, /dev/zero or a directory must be refused at
// once, never block. The first byte picks the form; every step is opened and read.
#include <sys/stat.h>

#include <vector>

#include "fuzz_input.h"
#include "tests/support/vtu_text.h"
#include "tsp/source/open_mesh_source.h"

namespace {

const char kStep[] =
    "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\"><vtkMultiBlockDataSet>"
    "<DataSet name=\"internal\" file=\"block.vtu\"/></vtkMultiBlockDataSet></VTKFile>";
const char* const kForms[] = {"input.vtm", "input.vtm.series", "input.vtu.series", "input.pvd"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const bool fixtures = [] {
    tspfuzz::write_input("block.vtu", reinterpret_cast<const std::uint8_t*>(tsptest::kOneTetVtu),
                         sizeof tsptest::kOneTetVtu - 1);
    tspfuzz::write_input("step.vtm", reinterpret_cast<const std::uint8_t*>(kStep),
                         sizeof kStep - 1);
    ::mkfifo((tspfuzz::scratch_dir() / "fifo.vtu").c_str(), 0600);
    return true;
  }();
  (void)fixtures;
  const std::string path = tspfuzz::write_input(kForms[data[0] % 4], data + 1, size - 1);
  tspfuzz::expect_clean([&] {
    auto s = tsp::open_mesh_source(path, "");
    for (int t = 0; t < s->steps(); ++t) {
      (void)s->bounds(t);
      (void)s->read_step(t);
    }
  });
  return 0;
}

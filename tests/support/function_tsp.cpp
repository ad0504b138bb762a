#include "support/function_tsp.h"

#include "support/memory_source.h"
#include "support/paths.h"
#include "tsp/build/build.h"

namespace tsptest {

std::string build_function_tsp(const std::string& name, tsp::Dims dims,
                               const std::function<float(int, int, int, int)>& f, int brick,
                               int steps) {
  auto src = MemorySource::from_function(dims, steps, f);
  const std::string path = (temp_dir() / (name + ".tsp")).string();
  tsp::BuildOptions o;
  o.brick_size = brick;
  o.range = tsp::ValueRange{0, 1};
  tsp::build_tsp_file(src, path, o);
  return path;
}

}  // namespace tsptest

// Throughput of the built-in datasets: seconds per step at a given size and thread count.
// Usage: generate_bench [NAME] [EDGE] [STEPS] [THREADS]   (defaults: shock 256 8 0 = all cores)
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/core/stopwatch.h"
#include "tsp/source/procedural/generate.h"

int main(int argc, char** argv) {
  const std::string name = argc > 1 ? argv[1] : "shock";
  const int edge = argc > 2 ? std::atoi(argv[2]) : 256;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 8;
  tsp::GenerateOptions o;
  o.dims = tsp::Dims{edge, edge, edge};
  o.steps = steps;
  o.threads = argc > 4 ? std::atoi(argv[4]) : 0;
  try {
    auto src = tsp::make_generated_source(name, o);
    std::vector<float> buf(std::size_t(src->dims().count()));
    double total = 0, worst = 0;
    for (int t = 0; t < src->steps(); ++t) {
      const tsp::Stopwatch watch;
      src->read_step(t, buf);
      const double s = watch.seconds();
      total += s;
      worst = s > worst ? s : worst;
    }
    std::printf("%s %s x %d steps, threads %d: %.3f s/step mean, %.3f s worst, %.1f Mvoxel/s\n",
                name.c_str(), tsp::to_string(src->dims()).c_str(), src->steps(), o.threads,
                total / src->steps(), worst,
                double(src->dims().count()) * src->steps() / total / 1e6);
  } catch (const tsp::Error& e) {
    std::fprintf(stderr, "generate_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}

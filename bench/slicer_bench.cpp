// Benchmark of slice polygon generation (spec §7): the incremental active-edge slicer vs the
// naive slicer (12 edge intersections + angular sort) on the same bricks and views in the same
// run. Each view slices every brick of a grid into one polygon soup, as a frame would; the soup
// is cleared, not freed, between views. Both slicers must produce the same polygon count. The
// slicers alternate view by view; each one's fastest of 3 passes over all views is reported.
//
//   slicer_bench [--views N] [--spacing S] [--seed K]   (defaults 100, 0.5, 1)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "tsp/core/stopwatch.h"
#include "tsp/frame/naive_slicer.h"
#include "tsp/frame/slicer.h"

namespace {

constexpr int kRepeats = 3;

struct Options {
  int views = 100;
  double spacing = 0.5;
  unsigned seed = 1;
};

// n³ bricks of `samples` samples per axis sharing one sample layer: geometric boxes of
// samples − 1 cells, tiling [0, n·(samples − 1)]³ (the octree's leaf bricks).
std::vector<tsp::Aabb> brick_grid(int n, int samples) {
  std::vector<tsp::Aabb> boxes;
  const double cells = samples - 1;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        boxes.push_back({{x * cells, y * cells, z * cells},
                         {(x + 1) * cells, (y + 1) * cells, (z + 1) * cells}});
  return boxes;
}

struct Result {
  double seconds = 0;
  std::size_t polygons = 0, vertices = 0;
};

// Times one frame (every brick, one view) into soup, cleared first; adds to r.
template <class SliceFrame>
void time_frame(const tsp::SlicePlanes& planes, SliceFrame& slice_frame, tsp::PolygonSoup& soup,
                Result& r) {
  soup.clear();
  const tsp::Stopwatch t0;
  slice_frame(planes, soup);
  r.seconds += t0.seconds();
  r.polygons += soup.size();
  r.vertices += soup.vertex_count();
}

bool bench_case(const char* name, int n, int samples, const Options& o) {
  const std::vector<tsp::Aabb> boxes = brick_grid(n, samples);
  std::mt19937 rng(o.seed);
  std::normal_distribution<double> g(0, 1);
  std::vector<tsp::SlicePlanes> views;
  for (int i = 0; i < o.views; ++i)
    views.push_back(tsp::SlicePlanes::toward({g(rng), g(rng), g(rng)}, o.spacing));

  auto incremental = [&](const tsp::SlicePlanes& planes, tsp::PolygonSoup& soup) {
    const tsp::IncrementalSlicer slicer(planes);  // once per frame: slopes and tie order
    for (const tsp::Aabb& b : boxes) slicer.slice(b, soup);
  };
  auto naive = [&](const tsp::SlicePlanes& planes, tsp::PolygonSoup& soup) {
    for (const tsp::Aabb& b : boxes) tsp::naive_slice(planes, b, soup);
  };
  // The two slicers alternate view by view, so load from other processes hits both alike; of
  // kRepeats passes over all views, each slicer's fastest counts.
  Result inc, nai;
  tsp::PolygonSoup soup_inc, soup_nai;
  for (int rep = 0; rep < kRepeats; ++rep) {
    Result ri, rn;
    for (const tsp::SlicePlanes& planes : views) {
      time_frame(planes, incremental, soup_inc, ri);
      time_frame(planes, naive, soup_nai, rn);
    }
    if (rep == 0 || ri.seconds < inc.seconds) inc = ri;
    if (rep == 0 || rn.seconds < nai.seconds) nai = rn;
  }
  const double inc_rate = double(inc.polygons) / inc.seconds;
  const double nai_rate = double(nai.polygons) / nai.seconds;
  std::printf("%s: %zu bricks of %d^3 samples, spacing %g, %d views, %.1f polygons/brick/view\n",
              name, boxes.size(), samples, o.spacing, o.views,
              double(inc.polygons) / double(boxes.size()) / o.views);
  std::printf("  incremental: %10.2f M polygons/s  (%6.1f ns/polygon, %.2f vertices/polygon)\n",
              inc_rate / 1e6, 1e9 / inc_rate, double(inc.vertices) / double(inc.polygons));
  std::printf("  naive:       %10.2f M polygons/s  (%6.1f ns/polygon)\n", nai_rate / 1e6,
              1e9 / nai_rate);
  std::printf("  ratio incremental/naive: %.1fx\n", inc_rate / nai_rate);
  if (inc.polygons != nai.polygons || inc.vertices != nai.vertices) {
    std::fprintf(stderr, "slicer_bench: polygon counts differ: %zu/%zu vs %zu/%zu\n", inc.polygons,
                 inc.vertices, nai.polygons, nai.vertices);
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (!std::strcmp(argv[i], "--views") && has_value) {
      o.views = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--spacing") && has_value) {
      o.spacing = std::atof(argv[++i]);
    } else if (!std::strcmp(argv[i], "--seed") && has_value) {
      o.seed = unsigned(std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "usage: slicer_bench [--views N] [--spacing S] [--seed K]\n");
      return 2;
    }
  }
  if (o.views < 1 || !(o.spacing > 0)) {
    std::fprintf(stderr, "slicer_bench: --views must be >= 1 and --spacing > 0\n");
    return 2;
  }
  bool ok = bench_case("large bricks", 9, 32, o);
  ok = bench_case("small bricks", 16, 8, o) && ok;
  return ok ? 0 : 1;
}

// Build throughput and peak memory of `build_tsp_file` against a naive builder, same input,
// same run.
//
//   build_bench [--dims N|X,Y,Z] [--steps T] [--threads N] [--brick B] [--no-naive] [--dir D]
//   build_bench --input FILE [--field NAME] [...]
//
// Default input: the built-in `shock` dataset at 256³ × 32 steps, written once to an HDF5 file in
// D (default $TMPDIR) and read once to warm the page cache, so both builders read it from memory.
// Target: ≥ 200 MB/s of float32 source voxels on 2 cores (taskset -c 0,1), peak RSS under
// 4 steps of data plus the tree. Each builder runs in its own child process, so each peak RSS is
// its own.
//
// The naive builder is what the TSP statistics cost without the streaming design: every step
// held in memory, every TSP node computed directly from its voxels with two-pass formulas
// (mean, then squared deviations; per-voxel temporal means, then deviations). It computes the
// statistics only (no quantization, no file), so the ratio flatters it. Its statistics are
// compared with the file's, which checks both.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench/support/bench_util.h"
#include "tsp/build/build.h"
#include "tsp/core/parallel_for.h"
#include "tsp/source/open_source.h"
#include "tsp/source/procedural/generate.h"
#include "tsp/store/tsp_file.h"

namespace {

namespace fs = std::filesystem;

struct Args {
  std::string input, field, dir = fs::temp_directory_path().string();
  tsp::Dims dims{256, 256, 256};
  int steps = 32, threads = 0, brick = tsp::kDefaultBrickSize;
  bool naive = true;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    std::string k = argv[i];
    auto val = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "build_bench: %s needs a value\n", k.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (k == "--input") a.input = val();
    else if (k == "--field") a.field = val();
    else if (k == "--dir") a.dir = val();
    else if (k == "--steps") a.steps = std::atoi(val().c_str());
    else if (k == "--threads") a.threads = std::atoi(val().c_str());
    else if (k == "--brick") a.brick = std::atoi(val().c_str());
    else if (k == "--no-naive") a.naive = false;
    else if (k == "--dims") {
      int x = 0, y = 0, z = 0;
      std::string v = val();
      int n = std::sscanf(v.c_str(), "%d,%d,%d", &x, &y, &z);
      a.dims = n == 1 ? tsp::Dims{x, x, x} : tsp::Dims{x, y, z};
    } else {
      std::fprintf(stderr, "build_bench: unknown option %s\n", k.c_str());
      std::exit(2);
    }
  }
  return a;
}

// Runs body(node, vsum, vdev) for every octree node on `threads` workers with per-worker buffers.
template <class Body>
void parallel_for_nodes(int nodes, int threads, const Body& body) {
  std::vector<std::array<std::vector<double>, 2>> buffers(
      std::size_t(tsp::parallel_workers(nodes, 1, threads)));
  tsp::parallel_for(nodes, 1, threads, [&](int w, std::int64_t first, std::int64_t last) {
    auto& b = buffers[std::size_t(w)];
    for (auto oid = first; oid < last; ++oid) body(int(oid), b[0], b[1]);
  });
}

// Fills tree's statistics by brute force from every step in memory.
void naive_statistics(tsp::TspTree& tree, const std::vector<std::vector<float>>& steps,
                      int threads) {
  const tsp::Octree& o = tree.octree();
  const tsp::TimeTree& time = tree.time();
  const tsp::Dims d = o.dims();
  const double width = tree.value_range().width();
  parallel_for_nodes(o.size(), threads, [&](int oid, std::vector<double>& vsum,
                                            std::vector<double>& vdev) {
    {
      const tsp::Box b = o.node(oid).box;
      const std::size_t n = std::size_t(b.count());
      for (int tid = 0; tid < time.size(); ++tid) {
        const tsp::Span s = time.span(tid);
        const double m = s.length(), N = double(n) * m;
        vsum.assign(n, 0.0);
        vdev.assign(n, 0.0);
        double sum = 0, lo = INFINITY, hi = -INFINITY;
        auto each = [&](auto&& f) {
          for (int t = s.t0; t <= s.t1; ++t) {
            std::size_t i = 0;
            for (int z = b.lo[2]; z < b.hi[2]; ++z)
              for (int y = b.lo[1]; y < b.hi[1]; ++y) {
                const float* row = steps[t].data() + (std::size_t(z) * d.y + y) * d.x;
                for (int x = b.lo[0]; x < b.hi[0]; ++x, ++i) f(i, double(row[x]));
              }
          }
        };
        each([&](std::size_t i, double v) {
          sum += v;
          vsum[i] += v;
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        });
        const double mean = sum / N;
        double dev = 0;
        each([&](std::size_t i, double v) {
          dev += (v - mean) * (v - mean);
          const double vm = vsum[i] / m;
          vdev[i] += (v - vm) * (v - vm);
        });
        double est = 0;
        for (std::size_t i = 0; i < n; ++i)
          est += tsp::coefficient_of_variation(std::sqrt(vdev[i] / m), vsum[i] / m, width);
        tsp::NodeStats& st = tree.stats(tree.id(oid, tid));
        st.mean = mean;
        st.std = std::sqrt(dev / N);
        st.min = float(lo);
        st.max = float(hi);
        st.spatial_error = float(tsp::coefficient_of_variation(st.std, mean, width));
        st.temporal_error = float(est / double(n));
      }
    }
  });
}

std::unique_ptr<tsp::VolumeSource> open_input(const Args& a, const std::string& path) {
  tsp::SourceOptions so;
  so.field = a.field;
  return tsp::open_source(path, so);
}

}  // namespace

int main(int argc, char** argv) {
  Args a = parse(argc, argv);
  const int threads = tsp::resolve_threads(a.threads);
  std::string input = a.input;
  if (input.empty()) {
    input = a.dir + "/build_bench_shock.h5";
    a.field = "shock";
    tsp::GenerateOptions g;
    g.dims = a.dims;
    g.steps = a.steps;
    auto src = tsp::make_generated_source("shock", g);
    std::printf("generating %s (shock %s x %d steps)...\n", input.c_str(),
                tsp::to_string(a.dims).c_str(), a.steps);
    std::fflush(stdout);
    tsp::write_generated_dataset(*src, input);
  }
  tspbench::warm_page_cache(input);
  const std::string out = a.dir + "/build_bench.tsp", naive_out = a.dir + "/build_bench.naive";

  auto tsp_run = tspbench::run_in_child([&] {
    try {
      auto src = open_input(a, input);
      tsp::BuildOptions opt;
      opt.field_name = a.field;
      opt.brick_size = a.brick;
      opt.threads = threads;
      tsp::build_tsp_file(*src, out, opt);
      return true;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "build_bench: %s\n", e.what());
      return false;
    }
  });
  if (!tsp_run.ok) return 1;
  auto file = tsp::TspFile::open(out);
  const tsp::TspTree& tree = file->tree();
  const tsp::Dims d = tree.octree().dims();
  const int T = tree.time().steps();
  const double mb = double(d.count()) * T * 4 / 1e6, step_mib = double(d.count()) * 4 / 1048576.0;
  std::printf("input   %s: %s x %d steps = %.1f MB of float32 (one step %.1f MiB), %d threads\n",
              input.c_str(), tsp::to_string(d).c_str(), T, mb, step_mib, threads);
  std::printf("tsp     %8.2f s  %8.1f MB/s  peak RSS %8.1f MiB (%.1f steps)  output %.1f MB\n",
              tsp_run.seconds, mb / tsp_run.seconds, tsp_run.peak_rss_mib,
              tsp_run.peak_rss_mib / step_mib, double(fs::file_size(out)) / 1e6);
  std::fflush(stdout);

  if (a.naive) {
    auto naive_run = tspbench::run_in_child([&] {
      auto src = open_input(a, input);
      std::vector<std::vector<float>> steps(std::size_t(T), std::vector<float>(std::size_t(d.count())));
      for (int t = 0; t < T; ++t) src->read_step(t, steps[std::size_t(t)]);
      tsp::TspTree naive(d, T, a.brick);
      naive.set_value_range(tree.value_range());
      naive_statistics(naive, steps, threads);
      std::ofstream f(naive_out, std::ios::binary);
      f.write(reinterpret_cast<const char*>(naive.all_stats().data()),
              std::streamsize(naive.all_stats().size_bytes()));
      return bool(f);
    });
    if (!naive_run.ok) return 1;
    std::vector<tsp::NodeStats> ns(std::size_t(tree.size()));
    std::ifstream f(naive_out, std::ios::binary);
    f.read(reinterpret_cast<char*>(ns.data()), std::streamsize(ns.size() * sizeof(tsp::NodeStats)));
    double worst = 0;  // largest difference relative to the value range (errors: absolute)
    const double w = tree.value_range().width() > 0 ? tree.value_range().width() : 1;
    for (int id = 0; id < tree.size(); ++id) {
      const tsp::NodeStats &p = tree.stats(id), &q = ns[std::size_t(id)];
      worst = std::max({worst, std::fabs(p.mean - q.mean) / w, std::fabs(p.std - q.std) / w,
                        std::fabs(double(p.min) - q.min) / w, std::fabs(double(p.max) - q.max) / w,
                        std::fabs(double(p.spatial_error) - q.spatial_error) /
                            std::max(1.0, double(std::fabs(q.spatial_error))),
                        std::fabs(double(p.temporal_error) - q.temporal_error) /
                            std::max(1.0, double(std::fabs(q.temporal_error)))});
    }
    std::printf("naive   %8.2f s  %8.1f MB/s  peak RSS %8.1f MiB (%.1f steps)\n", naive_run.seconds,
                mb / naive_run.seconds, naive_run.peak_rss_mib, naive_run.peak_rss_mib / step_mib);
    std::printf("ratio   tsp is %.1fx faster than naive, with %.1fx less memory; "
                "statistics agree to %.2g\n",
                naive_run.seconds / tsp_run.seconds, naive_run.peak_rss_mib / tsp_run.peak_rss_mib,
                worst);
    fs::remove(naive_out);
  }
  fs::remove(out);
  return 0;
}

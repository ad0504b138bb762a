// Build throughput and peak memory of `build_tsp_file`.
//
//   build_bench [X Y Z STEPS [BRICK [THREADS [OUT_DIR]]]]           synthetic float32 series
//   build_bench --input FILE [--field NAME] [BRICK [THREADS [OUT_DIR]]]   any tspplay input
//
// Default: synthetic 256³ × 32 steps, brick 32, all cores, output in $TMPDIR. The target is
// ≥ 200 MB/s of float32 source voxels from a warm page cache on 2 cores (taskset -c 0,1) with a
// peak RSS under 4 steps of data plus the tree. For the file form, e.g.
//   tspplay generate shock --dims 256 --steps 32 -o /tmp/shock.h5
//   taskset -c 0,1 build/build_bench --input /tmp/shock.h5
// The file is read once first to warm the page cache; the build runs in a child process so the
// reported peak RSS is the build's own.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/support/bench_util.h"
#include "tsp/build.h"
#include "tsp/tsp_file.h"

namespace {

// A smooth field that drifts over time; each step costs one pass over a precomputed base step,
// far less than the build itself (the base step is counted in the peak RSS, and reported).
class SyntheticSource : public tsp::VolumeSource {
 public:
  SyntheticSource(tsp::Dims d, int steps) : dims_(d), steps_(steps), base_(std::size_t(d.count())) {
    std::size_t i = 0;
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x, ++i)
          base_[i] = float(std::sin(0.05 * x) * std::cos(0.07 * y) + 0.01 * z);
  }
  tsp::Dims dims() const override { return dims_; }
  int steps() const override { return steps_; }
  std::string describe() const override { return "synthetic " + tsp::to_string(dims_); }
  void read_step(int t, std::span<float> out) override {
    const float shift = 0.02f * float(t);
    for (std::size_t i = 0; i < base_.size(); ++i) out[i] = base_[i] * (1.f + shift) + shift;
  }

 private:
  tsp::Dims dims_;
  int steps_;
  std::vector<float> base_;
};

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string input, field;
  tsp::Dims d{256, 256, 256};
  int steps = 32;
  std::size_t next = 0;
  if (!args.empty() && args[0] == "--input" && args.size() >= 2) {
    input = args[1];
    next = 2;
    if (args.size() >= 4 && args[2] == "--field") field = args[3], next = 4;
  } else if (args.size() >= 4) {
    d = {std::atoi(args[0].c_str()), std::atoi(args[1].c_str()), std::atoi(args[2].c_str())};
    steps = std::atoi(args[3].c_str());
    next = 4;
  }
  tsp::BuildOptions opt;
  opt.field_name = field;
  if (args.size() > next) opt.brick_size = std::atoi(args[next].c_str());
  if (args.size() > next + 1) opt.threads = std::atoi(args[next + 1].c_str());
  std::string dir =
      args.size() > next + 2 ? args[next + 2] : std::filesystem::temp_directory_path().string();
  const std::string out = dir + "/build_bench.tsp";

  if (!input.empty()) tspbench::warm_page_cache(input);
  auto run = tspbench::run_in_child([&] {
    try {
      std::unique_ptr<tsp::VolumeSource> src;
      if (input.empty()) {
        src = std::make_unique<SyntheticSource>(d, steps);
      } else {
        tsp::SourceOptions so;
        so.field = field;
        src = tsp::open_source(input, so);
      }
      const tsp::Dims dims = src->dims();
      auto t0 = std::chrono::steady_clock::now();
      std::string phase;
      opt.progress = [&](const std::string& p, std::int64_t, std::int64_t) {
        if (p == phase) return;
        double now = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::printf("  %-8s starts at %.2f s\n", p.c_str(), now);
        phase = p;
      };
      tsp::BuildReport r = tsp::build_tsp_file(*src, out, opt);
      const double mb = double(r.source_bytes) / 1e6, step_mb = double(dims.count()) * 4 / 1e6;
      std::printf("%s x %d steps, brick %d: %.1f MB in %.2f s = %.1f MB/s\n",
                  src->describe().c_str(), src->steps(), opt.brick_size, mb, r.seconds,
                  mb / r.seconds);
      std::printf("one step = %.1f MB%s; output %.1f MB\n", step_mb,
                  input.empty() ? " (the synthetic source holds one more)" : "",
                  double(std::filesystem::file_size(out)) / 1e6);
      std::fflush(stdout);
      return true;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "build_bench: %s\n", e.what());
      return false;
    }
  });
  std::filesystem::remove(out);
  if (!run.ok) return 1;
  std::printf("peak RSS %.1f MiB\n", run.peak_rss_mib);
  return 0;
}

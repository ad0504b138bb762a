// Build throughput and peak memory on a synthetic float32 series (default 256³ × 32 steps).
// Usage: build_bench [X Y Z STEPS [BRICK [THREADS [OUT_DIR]]]]
// Prints MB/s of float32 source voxels and the peak RSS; the target is ≥ 200 MB/s on 2 cores with
// peak RSS under 4 steps of data plus the tree.
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tsp/build.h"
#include "tsp/tsp_file.h"

namespace {

// A smooth field that drifts over time; each step costs one pass over a precomputed base step,
// far less than the build itself.
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

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

}  // namespace

int main(int argc, char** argv) {
  tsp::Dims d{256, 256, 256};
  int steps = 32, brick = tsp::kDefaultBrickSize, threads = 0;
  std::string dir = std::filesystem::temp_directory_path().string();
  if (argc >= 5)
    d = {std::atoi(argv[1]), std::atoi(argv[2]), std::atoi(argv[3])}, steps = std::atoi(argv[4]);
  if (argc >= 6) brick = std::atoi(argv[5]);
  if (argc >= 7) threads = std::atoi(argv[6]);
  if (argc >= 8) dir = argv[7];
  SyntheticSource src(d, steps);
  const double rss_before = peak_rss_mb();
  const std::string out = dir + "/build_bench.tsp";
  tsp::BuildOptions opt;
  opt.brick_size = brick;
  opt.threads = threads;
  double last = 0;
  std::string phase;
  auto t0 = std::chrono::steady_clock::now();
  opt.progress = [&](const std::string& p, std::int64_t, std::int64_t) {
    if (p != phase) {
      double now = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (!phase.empty()) std::printf("  phase %-8s %.2f s\n", phase.c_str(), now - last);
      phase = p;
      last = now;
    }
  };
  tsp::BuildReport r = tsp::build_tsp_file(src, out, opt);
  std::printf("  phase %-8s %.2f s\n", phase.c_str(), r.seconds - last);
  const double mb = double(r.source_bytes) / 1e6;
  const double step_mb = double(d.count()) * 4 / 1e6;
  std::printf("build %s x %d steps, brick %d: %.1f MB in %.2f s = %.1f MB/s\n",
              tsp::to_string(d).c_str(), steps, brick, mb, r.seconds, mb / r.seconds);
  std::printf(
      "peak RSS %.1f MB (synthetic source's base step %.1f MB, before build %.1f MB); "
      "one step = %.1f MB\n",
      peak_rss_mb(), step_mb, rss_before, step_mb);
  std::printf("output %.1f MB\n", double(std::filesystem::file_size(out)) / 1e6);
  std::filesystem::remove(out);
  return 0;
}

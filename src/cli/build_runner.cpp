#include "cli/build_runner.h"

#include <csignal>
#include <cstdio>

#include "cli/progress_bar.h"
#include "tsp/core/error.h"
#include "tsp/store/tsp_file.h"

namespace tspcli {
namespace {

// Set by SIGINT/SIGTERM; the progress callback turns it into an exception, so the build unwinds
// and removes its temporary file instead of leaving it behind.
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_interrupt(int) { g_interrupted = 1; }

// Installs the interrupt handlers for its lifetime.
class InterruptScope {
 public:
  InterruptScope()
      : old_int_(std::signal(SIGINT, on_interrupt)), old_term_(std::signal(SIGTERM, on_interrupt)) {}
  ~InterruptScope() {
    std::signal(SIGINT, old_int_);
    std::signal(SIGTERM, old_term_);
  }
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  void (*old_int_)(int);
  void (*old_term_)(int);
};

}  // namespace

tsp::BuildReport build_with_progress(tsp::VolumeSource& source, const std::string& out_path,
                                     tsp::BuildOptions options) {
  ProgressBar bar;
  options.progress = [&bar](const std::string& phase, std::int64_t done, std::int64_t total) {
    if (g_interrupted) throw tsp::Error("interrupted; no output written");
    bar.update(phase, done, total);
  };
  tsp::BuildReport r;
  {
    InterruptScope scope;
    try {
      r = tsp::build_tsp_file(source, out_path, options);
    } catch (...) {
      bar.finish();
      throw;
    }
    bar.finish();
  }
  if (r.nonfinite_count > 0)
    std::fprintf(
        stderr,
        "tspplay: warning: %lld NaN/Inf samples replaced (NaN and -Inf by %g, +Inf by %g)\n",
        static_cast<long long>(r.nonfinite_count), r.value_range.lo, r.value_range.hi);
  return r;
}

void print_build_summary(const std::string& out_path, const tsp::BuildReport& r) {
  auto file = tsp::TspFile::open(out_path);
  const tsp::TspTree& tree = file->tree();
  const double mb = double(r.source_bytes) / 1e6;
  std::printf("wrote %s: %s voxels, %d steps, brick %d: %d bricks, %d TSP nodes\n",
              out_path.c_str(), tsp::to_string(tree.octree().dims()).c_str(), tree.time().steps(),
              tree.octree().brick_size(), tree.octree().brick_count(), tree.size());
  std::printf("value range [%g, %g], data range [%g, %g]; %.1f MB in %.2f s (%.1f MB/s)\n",
              r.value_range.lo, r.value_range.hi, r.data_range.lo, r.data_range.hi, mb, r.seconds,
              r.seconds > 0 ? mb / r.seconds : 0.0);
}

}  // namespace tspcli

#include "cli/build_runner.h"

#include <cstdio>

#include "cli/progress_bar.h"
#include "tsp/core/error.h"
#include "tsp/core/interrupt.h"
#include "tsp/store/tsp_file.h"

namespace tspcli {
namespace {

// The partition of tspplay-mpi's build (set once by its main); null in tspplay.
tsp::BuildPartition* g_partition = nullptr;
int g_partition_threads = 0;  // worker threads per process when --threads is not given

}  // namespace

namespace {

// Runs build(options) with a progress bar and clean Ctrl-C, then warns of replaced samples.
template <class Build>
auto run_with_progress(tsp::BuildOptions options, const Build& build) {
  ProgressBar bar;
  options.partition = g_partition;
  if (g_partition && options.threads == 0) options.threads = g_partition_threads;
  const bool writer = build_writes_output();  // other ranks show no bar
  options.progress = [&bar, writer](const std::string& phase, std::int64_t done,
                                    std::int64_t total) {
    // SIGINT/SIGTERM: the build unwinds and removes its temporary file.
    tsp::throw_if_interrupted();
    if (writer) bar.update(phase, done, total);
  };
  const tsp::InterruptScope scope;  // main's, or tspplay-mpi's when it has none
  try {
    auto r = build(options);
    bar.finish();
    return r;
  } catch (...) {
    bar.finish();
    throw;
  }
}

void warn_nonfinite(const tsp::BuildReport& r, const std::string& field) {
  if (r.nonfinite_count > 0 && build_writes_output())
    std::fprintf(
        stderr,
        "tspplay: warning: %s%lld NaN/Inf samples replaced (NaN and -Inf by %g, +Inf by %g)\n",
        field.empty() ? "" : (field + ": ").c_str(), static_cast<long long>(r.nonfinite_count),
        r.value_range.lo, r.value_range.hi);
}

}  // namespace

void set_build_partition(tsp::BuildPartition* partition, int threads) {
  g_partition = partition;
  g_partition_threads = threads;
}

bool build_writes_output() { return !g_partition || g_partition->rank() == 0; }

tsp::BuildReport build_with_progress(tsp::VolumeSource& source, const std::string& out_path,
                                     tsp::BuildOptions options) {
  const tsp::BuildReport r = run_with_progress(options, [&](const tsp::BuildOptions& o) {
    return tsp::build_tsp_file(source, out_path, o);
  });
  warn_nonfinite(r, "");
  return r;
}

std::vector<tsp::BuildReport> build_fields_with_progress(const tsp::FieldSourceFn& open_field,
                                                         const std::vector<std::string>& fields,
                                                         const std::string& out_path,
                                                         tsp::BuildOptions options) {
  const std::vector<tsp::BuildReport> reports =
      run_with_progress(options, [&](const tsp::BuildOptions& o) {
        return tsp::build_tsp_fields(open_field, fields, out_path, o);
      });
  for (std::size_t k = 0; k < reports.size(); ++k) warn_nonfinite(reports[k], fields[k]);
  return reports;
}

tsp::AdaptiveReport build_adaptive_with_progress(tsp::MeshSource& source,
                                                 const std::string& out_path,
                                                 tsp::AdaptiveOptions options) {
  if (g_partition)
    throw tsp::UsageError("--octree-error: tspplay-mpi has no adaptive build; use tspplay build");
  const tsp::AdaptiveReport r = run_with_progress(options.build, [&](const tsp::BuildOptions& o) {
    tsp::AdaptiveOptions with = options;
    with.build = o;
    return tsp::build_adaptive_tsp(source, out_path, with);
  });
  warn_nonfinite(r.build, "");
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

void print_adaptive_summary(const std::string& out_path, const tsp::AdaptiveReport& r) {
  print_build_summary(out_path, r.build);
  std::printf("adaptive octree (E = %g): %d of %d nodes hold data, %d stopped above the finest "
              "level; bricks %.1f MB of the uniform build's %.1f MB; cell lists %.1f MB; "
              "octree %.2f s, voxelizing %.2f s\n",
              r.threshold, r.nodes, r.complete_nodes, r.stopped, double(r.brick_bytes) / 1e6,
              double(r.complete_brick_bytes) / 1e6, double(r.cell_list_bytes) / 1e6,
              r.octree_seconds, r.voxelize_seconds);
}

}  // namespace tspcli

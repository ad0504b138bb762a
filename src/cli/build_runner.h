// Running a build from the command line: progress bar, clean Ctrl-C, the closing summary.
#pragma once
#include <string>
#include <vector>

#include "tsp/adaptive/adaptive_build.h"
#include "tsp/build/build.h"

namespace tspcli {

/// Makes every later build of this process its share of a build split over processes
/// (tspplay-mpi's main, before parsing; null: the whole build), with `threads` workers each
/// unless --threads says (0: all cores). Not thread-safe.
void set_build_partition(tsp::BuildPartition* partition, int threads);

/// Whether this process writes the output (always, unless it is a rank other than 0 of a
/// partitioned build). Never throws.
bool build_writes_output();

/// Builds out_path from source with a progress bar on a terminal; SIGINT/SIGTERM cancel the
/// build cleanly (no output, no temporary file) by throwing tsp::Error. Prints the NaN/Inf
/// warning. Throws whatever build_tsp_file throws.
tsp::BuildReport build_with_progress(tsp::VolumeSource& source, const std::string& out_path,
                                     tsp::BuildOptions options);

/// Builds several fields of one input into out_path (tsp::build_tsp_fields) with the same
/// progress bar and Ctrl-C handling. Throws whatever build_tsp_fields throws.
std::vector<tsp::BuildReport> build_fields_with_progress(const tsp::FieldSourceFn& open_field,
                                                         const std::vector<std::string>& fields,
                                                         const std::string& out_path,
                                                         tsp::BuildOptions options);

/// Builds out_path from a mesh series with an adaptive octree (tsp::build_adaptive_tsp) with the
/// same progress bar and Ctrl-C handling. Throws UsageError in a build split over processes
/// (tspplay-mpi has no adaptive build), else whatever build_adaptive_tsp throws.
tsp::AdaptiveReport build_adaptive_with_progress(tsp::MeshSource& source,
                                                 const std::string& out_path,
                                                 tsp::AdaptiveOptions options);

/// Prints "wrote OUT: ..." with the tree's size, ranges and throughput (reopens the file).
void print_build_summary(const std::string& out_path, const tsp::BuildReport& report);

/// print_build_summary, then "adaptive octree (E = ...): ..." with the octree's size and times.
void print_adaptive_summary(const std::string& out_path, const tsp::AdaptiveReport& report);

}  // namespace tspcli

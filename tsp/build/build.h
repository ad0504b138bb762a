// tsp/build: turning a VolumeSource into a .tsp file; may include core/, source/, tree/, store/.
// Building a .tsp file from a VolumeSource: bricks, the TSP tree and its statistics.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tsp/build/build_partition.h"
#include "tsp/core/temp_output.h"
#include "tsp/core/types.h"
#include "tsp/source/volume_source.h"

namespace tsp {

/// Progress callback: phase name ("reading", "bricks"), units done, units total (bytes of source
/// data). Called from one thread at a time, not necessarily the caller's. It may throw to cancel
/// the build: the exception reaches the caller and no output or temporary file remains.
using ProgressFn =
    std::function<void(const std::string& phase, std::int64_t done, std::int64_t total)>;

/// Throws FormatError "WHAT: the time of step K is X; step times must be finite numbers" for
/// the first non-finite time (the .tsp reader refuses them: a build refuses them first).
void check_step_times(const std::string& what, const std::vector<double>& times);

/// The brick size `tspplay build` uses unless told: the power of two nearest a quarter of the
/// grid's longest edge, in [8, 64] — about four bricks per axis, so transparent and coherent
/// regions split off while the one-pass ray caster crosses few bricks per ray (64³ → 16,
/// 128³ → 32, 256³ and beyond → 64; measured in docs/results.md). Never throws.
int default_brick_size(Dims dims);

/// Options of `tspplay build`.
struct BuildOptions {
  int brick_size = kDefaultBrickSize;  ///< B, a power of two
  std::optional<ValueRange> range;     ///< quantization range; default: the data's finite range
  int threads = 0;                     ///< worker threads; 0 = hardware concurrency
  std::string field_name;              ///< recorded in the file (empty: the one the source picked)
  ProgressFn progress;                 ///< may be empty
  /// The grid's physical position and voxel spacing, instead of what the source says (positive,
  /// finite spacing; finite origin — checked by build_tsp_file).
  std::optional<std::array<double, 3>> origin, spacing;
  /// Non-null: this process builds its share of a build split over processes (tspplay-mpi);
  /// only rank 0 writes out_path, the others return after handing it their bricks.
  BuildPartition* partition = nullptr;
  /// 1–9: brick chunks compressed with shuffle + deflate at that level (`build --compress`);
  /// 0: stored as is. Readers need nothing (HDF5 decompresses). Checked by the build.
  int deflate = 0;
  /// What an out_path that is a symbolic link replaces: its target (`build -o link`), or the
  /// link itself (play's build cache, where another user may have planted it).
  OutputLinks output_links = OutputLinks::follow;
};

/// What a build did, for the CLI and the benchmark.
struct BuildReport {
  std::int64_t source_bytes = 0;     ///< voxels × steps × 4 (float samples read)
  std::int64_t nonfinite_count = 0;  ///< NaN/Inf samples replaced
  double seconds = 0;                ///< wall time of the whole build
  ValueRange data_range;             ///< finite min/max of the input ({0, 0} when none)
  ValueRange value_range;            ///< quantization range written to the file
};

/// Most fields build_tsp_fields puts in one file (open_input_fields opens an HDF5 input once
/// for all of them; each field is then built like a file of its own).
inline constexpr int kMaxBuildFields = 4096;

/// Opens the source of one named field of the input (build_tsp_fields).
using FieldSourceFn = std::function<std::unique_ptr<VolumeSource>(const std::string& field)>;

/// Builds several fields of one input into one .tsp file, one tree each, in the order given: the
/// first at the file's root (so every reader sees it), the others in groups fields/1, fields/2, …
/// with the list in the root attribute `fields` (docs/formats.md). Each field is built like
/// build_tsp_file, reading its own source (open_field(name)) on its own grid (dims, origin,
/// spacing: WRF's staggered fields keep theirs); all must have the first field's steps.
/// options.field_name is ignored (each field gets its name); progress phases are prefixed with
/// the field. One report per field. Throws like build_tsp_file, and FormatError for a field
/// with other steps; never leaves a partial out_path.
std::vector<BuildReport> build_tsp_fields(const FieldSourceFn& open_field,
                                          const std::vector<std::string>& fields,
                                          const std::string& out_path, const BuildOptions& options);

/// Reads every step of source once, writes out_path (via a temporary name renamed at the end),
/// and returns what it did. Samples are clamped to the quantization range (NaN and −Inf become
/// its lo, +Inf its hi) before statistics and quantization. Throws IoError/FormatError/
/// UsageError (bad brick size or range); never leaves a partial out_path or a temporary file.
BuildReport build_tsp_file(VolumeSource& source, const std::string& out_path,
                           const BuildOptions& options);

}  // namespace tsp

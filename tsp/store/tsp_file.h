// The .tsp file: an HDF5 file holding quantized leaf bricks and the TSP tree with statistics.
// Layout and versioning: docs/formats.md.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tsp/core/geometry.h"
#include "tsp/core/time_text.h"
#include "tsp/store/brick_store.h"

namespace tsp {

/// Format version written by this build; readers accept exactly this version (2: LOD level
/// bricks after the leaf bricks, spec §14).
inline constexpr int kTspFormatVersion = 2;
/// Version of a file whose octree stops above the finest level at some nodes (an adaptive build,
/// `build MESH --octree-error`): version 2 plus octree/stopped. Readers accept both; an older
/// tspplay refuses it rather than drawing the absent bricks.
inline constexpr int kTspAdaptiveFormatVersion = 3;
/// Bins of the value histogram stored in the file (over the quantization range).
inline constexpr int kHistogramBins = 256;

/// Everything in a .tsp file besides the tree and the bricks.
struct TspMetadata {
  std::string source;                  ///< what was read (VolumeSource::describe())
  std::string field;                   ///< field name, may be empty
  ValueRange data_range;               ///< min and max of the finite input samples
  std::int64_t nonfinite_count = 0;    ///< NaN/Inf samples replaced by the NaN/Inf rule
  std::vector<std::uint64_t> histogram;  ///< kHistogramBins counts over value_range()
  std::string created_by;              ///< "tspplay VERSION"
  std::array<double, 3> origin{0, 0, 0};   ///< physical position of voxel (0, 0, 0)
  std::array<double, 3> spacing{1, 1, 1};  ///< physical voxel spacing per axis
  int build_ranks = 1;  ///< processes that built the file (tspplay-mpi ranks; 1: serial)
  int deflate = 0;      ///< deflate level of the bricks (build --compress; read, not written)
  std::vector<double> times;  ///< physical time of every step, when the input named them
  TimeUnits time_units;       ///< the units of times (CF units/calendar), when the input named them
};

/// An open .tsp file: tree, metadata, and brick reads (one HDF5 chunk per brick and step).
class TspFile : public BrickStore {
 public:
  /// Opens path and loads the tree of `field` (empty: the file's first field); throws IoError
  /// (missing/unreadable), FormatError (not a .tsp file, other version, inconsistent contents),
  /// naming the file, or UsageError (no such field: the message lists the file's fields).
  static std::unique_ptr<TspFile> open(const std::string& path, const std::string& field = "");
  ~TspFile() override;
  /// The tree with every node's statistics.
  const TspTree& tree() const override;
  /// metadata().histogram.
  std::span<const std::uint64_t> histogram() const override { return metadata().histogram; }
  /// Provenance, ranges, histogram.
  const TspMetadata& metadata() const;
  /// Path the file was opened from.
  const std::string& path() const;
  /// Every field the file holds, in order (one for a file built with one field; its name may be
  /// empty).
  const std::vector<std::string>& fields() const;
  /// Which of fields() this one is.
  int field_index() const;
  /// The physical box every field of the file lies in: the union over fields of origin ..
  /// origin + (dims − 1)·spacing (fields may lie on different grids, as WRF's staggered ones).
  /// Views fit this box, so that switching fields keeps them in place. Never throws.
  const Aabb& frame() const;
  /// Reads one stored brick (leaf or level) at one step; thread-safe. Throws IoError/FormatError.
  void read_brick(int brick, int step, std::span<std::uint16_t> out) const override;
  /// Reads one stored brick's stencil at one step (files with a stencil); thread-safe. Throws
  /// IoError/FormatError.
  void read_inside(int brick, int step, std::span<std::uint8_t> out) const override;

  /// The open file's state (opaque: defined and read in tsp_file.cpp).
  struct Impl;

 private:
  explicit TspFile(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tsp

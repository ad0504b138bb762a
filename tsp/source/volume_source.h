// tsp/source: where time series come from — this interface, open_source() and the readers;
// may include core/, hdf5/ and source/vtk/.
// The one interface every reader feeds: a scalar field on a regular grid over T time steps.
// Later importers (unstructured-grid voxelizer, multiresolution levels) plug in here too.
#pragma once
#include <array>
#include <cassert>
#include <cstdint>
#include <memory>
#include <optional>
#include <algorithm>
#include <span>
#include <string>
#include <vector>

#include "tsp/core/time_text.h"
#include "tsp/core/types.h"

namespace tsp {

/// A time series of one 3-D scalar field, read one step at a time.
class VolumeSource {
 public:
  virtual ~VolumeSource() = default;
  /// Grid size, the same for every step.
  virtual Dims dims() const = 0;
  /// Number of time steps T ≥ 1.
  virtual int steps() const = 0;
  /// Names what is read ("file.h5, dataset /T"), for messages and the .tsp file's provenance.
  virtual std::string describe() const = 0;
  /// Every file it reads (empty for a source computed in memory), so that an output is never
  /// written over an input. Never throws.
  virtual std::vector<std::string> files() const { return {}; }
  /// Reads step t (0 ≤ t < steps()) into out, dims().count() floats, x fastest then y then z.
  /// Non-finite values are passed through; the builder applies the NaN/Inf rule.
  /// Throws IoError or FormatError naming the file and field.
  virtual void read_step(int t, std::span<float> out) = 0;
  /// True when read_slab reads planes of a step without reading the rest, so that a builder
  /// holds slabs instead of whole steps. Never throws.
  virtual bool reads_slabs() const { return false; }
  /// Planes per read_slab that suit how the input is stored (an HDF5 chunk's depth: slabs that
  /// are multiples of it, starting at 0, read each chunk once); 0 when any height suits. Never
  /// throws.
  virtual int slab_alignment() const { return 0; }
  /// Reads planes z0 … z1 − 1 (0 ≤ z0 < z1 ≤ dims().z) of step t into out ((z1 − z0) · d.x · d.y
  /// floats, x fastest) as read_step would; called only when reads_slabs(). Throws like
  /// read_step.
  virtual void read_slab(int /*t*/, int /*z0*/, int /*z1*/, std::span<float> /*out*/) {
    assert(false && "read_slab of a source that does not read slabs");
  }
  /// True when some voxels may lie outside the data (a voxelized unstructured mesh): then
  /// read_step_inside says which, and a builder stores the stencil. Never throws.
  virtual bool has_stencil() const { return false; }
  /// Reads step t like read_step and its stencil into inside (dims().count() bytes, 1 = inside
  /// the data, 0 = outside; outside samples hold padding). The default reads read_step and
  /// marks every voxel inside. Throws like read_step.
  virtual void read_step_inside(int t, std::span<float> out, std::span<std::uint8_t> inside) {
    read_step(t, out);
    std::fill(inside.begin(), inside.end(), std::uint8_t(1));
  }
  /// Physical time of every step when the input names them (.pvd timesteps, .series times,
  /// VTKHDF Steps/Values, an HDF5 time dimension scale); empty when it does not. Never throws.
  virtual std::vector<double> times() const { return {}; }
  /// The units of times() when the input names them (CF `units`/`calendar` of the time
  /// coordinate, WRF `Times` as "seconds since" the first date); empty otherwise. Never throws.
  virtual TimeUnits time_units() const { return {}; }
  /// Physical position of voxel (0, 0, 0); (0, 0, 0) when the input does not say. Never throws.
  virtual std::array<double, 3> origin() const { return {0, 0, 0}; }
  /// Physical distance between neighbouring voxels per axis; (1, 1, 1) when the input does not
  /// say. Never throws.
  virtual std::array<double, 3> spacing() const { return {1, 1, 1}; }
  /// The field it reads, as `--field` would name it — the one it picked when none was named (a
  /// file's only dataset, a mesh's active scalars) — so builds record it for legends and file
  /// names; empty when the input names none (a raw series). Never throws.
  virtual std::string field() const { return {}; }
};

/// Element types of raw input files.
enum class RawType { u8, u16, f32 };

/// The uniform vertical grid an input with uneven levels (WRF's, at their geopotential heights)
/// is resampled to (tsp/source/level_resample.h; `--vertical-levels`).
struct VerticalLevels {
  enum class Mode {
    finest,   ///< the finest layer's spacing, capped at kFinestLevelsCap levels (default)
    native,   ///< no resampling: the levels as stored, at their mean spacing
    count,    ///< `levels` levels over the heights' range
    spacing,  ///< `spacing` metres apart
  };
  Mode mode = Mode::finest;
  int levels = 0;       ///< Mode::count
  double spacing = 0;   ///< Mode::spacing, metres
  bool operator==(const VerticalLevels&) const = default;
};

/// How to open an input; fields not relevant to the input's kind are ignored.
struct SourceOptions {
  std::string field;                    ///< dataset / variable / array name; empty: the only one
  std::optional<Dims> raw_dims;         ///< raw series: grid size (required for raw input)
  RawType raw_type = RawType::f32;      ///< raw series: element type
  bool raw_big_endian = false;          ///< raw series: byte order
  bool allow_external = false;  ///< HDF5: read external links, external storage and virtual
                                ///< datasets (h5::check_external; `--allow-external`)
  std::string plot3d_grid;  ///< PLOT3D: the .q solutions' grid (.xyz; empty: the only one beside)
  VerticalLevels vertical;  ///< WRF: levels resampled at their heights (`--vertical-levels`)
};

}  // namespace tsp

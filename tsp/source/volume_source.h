// tsp/source: where time series come from — this interface, open_source() and the readers;
// may include core/, hdf5/ and source/vtk/.
// The one interface every reader feeds: a scalar field on a regular grid over T time steps.
// Later importers (unstructured-grid voxelizer, multiresolution levels) plug in here too.
#pragma once
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

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
};

/// Element types of raw input files.
enum class RawType { u8, u16, f32 };

/// How to open an input; fields not relevant to the input's kind are ignored.
struct SourceOptions {
  std::string field;                    ///< dataset / variable / array name; empty: the only one
  std::optional<Dims> raw_dims;         ///< raw series: grid size (required for raw input)
  RawType raw_type = RawType::f32;      ///< raw series: element type
  bool raw_big_endian = false;          ///< raw series: byte order
};

}  // namespace tsp

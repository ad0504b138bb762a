// Writes any VolumeSource to an HDF5 file as one 4-D float32 dataset /NAME of shape (T, Z, Y, X),
// the layout the HDF5 reader opens with open_source(path, {.field = NAME}).
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "tsp/source/volume_source.h"

namespace tsp {

/// One attribute stored on the dataset: a scalar, a string or a 1-D integer array.
struct Hdf5Attribute {
  std::string name;
  std::variant<std::int64_t, std::uint64_t, double, std::string, std::vector<std::int64_t>> value;
};

/// Largest chunk the writer makes; a chunk is one step, or a slab of whole z-slices of one step.
inline constexpr std::int64_t kMaxChunkBytes = 4 << 20;
/// Largest gzip (deflate) level.
inline constexpr int kMaxGzipLevel = 9;

/// What to write besides the values.
struct Hdf5WriteOptions {
  std::string dataset;                    ///< dataset name below the root, no '/'; required
  std::vector<Hdf5Attribute> attributes;  ///< extra attributes on the dataset
  int gzip_level = 0;                     ///< 0: uncompressed; 1..9: shuffle + deflate
};

/// Writes every step of source to path. The dataset always gets the attributes dims (int64[3],
/// x y z), steps, axes ("t,z,y,x") and source (describe()), then options.attributes. Writes to a
/// hidden temporary file beside path and renames it over path at the end, so path is either
/// untouched or complete; the temporary file is removed on any error. Throws UsageError (bad
/// dataset name, gzip level or attribute name), IoError (cannot create, write or rename), and
/// whatever source.read_step throws.
void write_hdf5(VolumeSource& source, const std::filesystem::path& path,
                const Hdf5WriteOptions& options);

}  // namespace tsp

// Opening several named fields of one input (build/play --field A,B,C): an HDF5 file is opened,
// checked and walked once for all of them, whatever their number.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tsp/source/volume_source.h"
#include "tsp/voxelize/voxelized_source.h"

namespace tsp {

/// Opens the source of one named field of an input.
using FieldOpener = std::function<std::unique_ptr<VolumeSource>(const std::string& field)>;

/// Most missing field names an error lists (then "… and N more").
inline constexpr std::size_t kMissingFieldsListed = 20;

/// An opener of the fields of input (open_input with options.field set to each). An HDF5 /
/// NetCDF-4 file (not a mesh) is opened and checked (external links and storage) here, once,
/// and every field of `fields` looked up before any is read: a FormatError names the missing
/// ones (at most kMissingFieldsListed, with their count) and the file's 3-D/4-D datasets; each
/// field's source then shares that open file. Other inputs are opened once per field. Throws
/// what open_input throws.
FieldOpener open_input_fields(const std::string& input, const SourceOptions& options,
                              const VoxelizeOptions& voxel, const std::vector<std::string>& fields);

/// The names `--field A,B,C` gives (build and play), split at every comma: {"A", "B", "C"};
/// empty for a single name (no comma). An empty name ("A,,B", "A,") is kept, for the lookup to
/// report missing. Never throws but bad_alloc.
std::vector<std::string> field_names(const std::string& field);

}  // namespace tsp

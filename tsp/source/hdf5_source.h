// Reader for HDF5 and NetCDF-4 files (and the VTKHDF ImageData files inside them).
#pragma once
#include <memory>
#include <string>

#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/source/volume_source.h"

namespace tsp::io {

/// Opens an HDF5 / NetCDF-4 file. A file with a /VTKHDF group is read as VTKHDF ImageData;
/// otherwise options.field names a 4-D (T,Z,Y,X) dataset, a 3-D (Z,Y,X) dataset (one step)
/// or a group of 3-D datasets (one per step, natural name order); an empty field picks the
/// only 4-D dataset. NetCDF scale_factor/add_offset are applied and _FillValue/missing_value
/// samples become NaN. Throws IoError (missing/unreadable file) or FormatError naming the
/// file, the field and what was expected versus found.
std::unique_ptr<VolumeSource> open_hdf5_source(const std::string& path,
                                               const SourceOptions& options);

/// The file open_hdf5_source reads, opened read-only and checked (a NetCDF classic file refused
/// with how to convert it; external links and storage per options.allow_external). Throws
/// IoError, FormatError, UsageError.
h5::Handle open_hdf5_file(const std::string& path, const SourceOptions& options);
/// open_hdf5_source on a file open_hdf5_file opened (a field of several sharing one open).
std::unique_ptr<VolumeSource> open_hdf5_source(const std::string& path, h5::Handle file,
                                               const SourceOptions& options);
/// The file's 3-D and 4-D datasets as "/path (shape)", comma-separated, for messages (walks the
/// file). Never throws.
std::string hdf5_candidates_text(hid_t file);

}  // namespace tsp::io

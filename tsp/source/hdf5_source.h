// Reader for HDF5 and NetCDF-4 files (and the VTKHDF ImageData files inside them).
#pragma once
#include <memory>
#include <string>

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

}  // namespace tsp::io

// Opening an input by its form: picks the reader (HDF5/NetCDF-4/VTKHDF, VTK image data, raw
// series) for a path or file pattern.
#pragma once
#include <memory>
#include <string>

#include "tsp/source/volume_source.h"

namespace tsp {

/// Opens INPUT by its form: .h5/.hdf5/.nc/.hdf (HDF5, NetCDF-4, VTKHDF), .pvd / .vti.series /
/// .vti (VTK image data), or a printf pattern / glob of raw files. Throws IoError/FormatError/UsageError.
std::unique_ptr<VolumeSource> open_source(const std::string& input, const SourceOptions& options);

/// True when open_source reads input as an HDF5 / NetCDF-4 / VTKHDF file: an existing regular
/// file with an HDF5 extension or signature. Never throws.
bool is_hdf5_input(const std::string& input);

}  // namespace tsp

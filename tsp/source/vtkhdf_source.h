// Reader for VTKHDF ImageData files (VTK's HDF5-based format), static or transient.
#pragma once
#include <hdf5.h>

#include <memory>
#include <string>

#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/source/volume_source.h"

namespace tsp::io {

/// True when the open HDF5 file has a /VTKHDF group (a VTKHDF file of any type). Never throws.
bool is_vtkhdf(hid_t file);

/// Reads the VTKHDF ImageData in `file` (opened from path): options.field names a PointData
/// array (else a CellData array, read as a grid of cells); empty picks the only array, else
/// the PointData "Scalars" array. A /VTKHDF/Steps group makes it transient (NSteps steps),
/// else it has 1 step. Throws FormatError naming the file, the field and what was expected
/// versus found.
std::unique_ptr<VolumeSource> open_vtkhdf_source(const std::string& path, h5::Handle file,
                                                 const SourceOptions& options);

}  // namespace tsp::io
